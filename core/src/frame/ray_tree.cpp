// The border rays' prefix tree (ray_tree.hpp).
#include "frame/ray_tree.hpp"

#include <algorithm>
#include <cstdlib>
#include <tuple>
#include <utility>

#include "base/bounded_cache.hpp"
#include "base/huge_pages.hpp"
#include "isolux/light_trace.hpp"

namespace isolux {

namespace {

std::shared_ptr<const RayTree> build_ray_tree(int a, int b, int k) {
    struct Node {
        std::int16_t dx, dy;
        std::int32_t child[8];
    };
    const auto border = border_offsets(a, b);
    // Room for the nodes up front, in huge pages (huge_pages.hpp): growing
    // by doubling copies every node built so far into fresh pages, which for
    // a light of a thousand pixels cost more than building the tree. A tree
    // has about 1.6 nodes an area pixel (docs/performance.md); twice the
    // pixels, bounded by the rays' steps, covers it.
    const std::size_t area_pixels = std::size_t(2 * a + 1) * std::size_t(2 * b + 1);
    const std::size_t ray_steps = (border.size() / std::size_t(k) + 1) * std::size_t(std::max(a, b) + 1);
    std::vector<Node> nodes;
    reserve_huge(nodes, std::min(2 * area_pixels, ray_steps) + 1);
    nodes.push_back({0, 0, {-1, -1, -1, -1, -1, -1, -1, -1}});
    for (std::size_t i = 0; i < border.size(); i += std::size_t(k)) {
        std::int32_t at = 0;
        BresenhamRay r(0, 0, border[i].first, border[i].second);
        for (r.step(); !r.done(); r.step()) {
            const int ddx = int(r.x) - nodes[at].dx, ddy = int(r.y) - nodes[at].dy;  // one of 8 neighbours
            const int dir = (ddy + 1) * 3 + (ddx + 1) - ((ddy + 1) * 3 + (ddx + 1) > 4);
            if (nodes[at].child[dir] < 0) {
                nodes[at].child[dir] = std::int32_t(nodes.size());
                nodes.push_back({std::int16_t(r.x), std::int16_t(r.y), {-1, -1, -1, -1, -1, -1, -1, -1}});
            }
            at = nodes[at].child[dir];
        }
    }
    auto tree = std::make_shared<RayTree>();
    reserve_huge(tree->dx, nodes.size());
    reserve_huge(tree->dy, nodes.size());
    assign_huge(tree->end, nodes.size());
    // Iterative depth-first flattening (children in a fixed order).
    std::vector<std::pair<std::int32_t, int>> stack = {{0, 0}};  // node, next child
    std::vector<std::int32_t> index_of;
    assign_huge(index_of, nodes.size());
    while (!stack.empty()) {
        auto& [n, c] = stack.back();
        if (c == 0) {
            index_of[n] = std::int32_t(tree->dx.size());
            tree->dx.push_back(nodes[n].dx);
            tree->dy.push_back(nodes[n].dy);
        }
        while (c < 8 && nodes[n].child[c] < 0) ++c;
        if (c < 8) {
            const std::int32_t child = nodes[n].child[c++];
            stack.push_back({child, 0});
        } else {
            tree->end[index_of[n]] = std::int32_t(tree->dx.size());
            stack.pop_back();
        }
    }
    assign_huge(tree->offset, tree->dx.size());
    assign_huge(tree->depth, tree->dx.size());
    for (std::size_t i = 0; i < tree->dx.size(); ++i) {
        tree->offset[i] = tree->dy[i] * (2 * a + 1) + tree->dx[i];
        tree->depth[i] = std::uint16_t(std::max(std::abs(tree->dx[i]), std::abs(tree->dy[i])));
    }
    const std::size_t pixels = std::size_t(2 * a + 1) * (2 * b + 1);
    const std::int32_t centre = b * (2 * a + 1) + a;
    assign_huge(tree->pixel_start, pixels + 1);
    for (std::int32_t o : tree->offset) ++tree->pixel_start[std::size_t(centre + o) + 1];
    for (std::size_t p = 0; p < pixels; ++p) tree->pixel_start[p + 1] += tree->pixel_start[p];
    assign_huge(tree->pixel_nodes, tree->offset.size());
    std::vector<std::int32_t> next(tree->pixel_start.begin(), tree->pixel_start.end() - 1);
    for (std::size_t i = 0; i < tree->offset.size(); ++i)
        tree->pixel_nodes[std::size_t(next[std::size_t(centre + tree->offset[i])]++)] = std::int32_t(i);
    assign_huge(tree->nodes_at, pixels);
    for (std::size_t p = 0; p < pixels; ++p) {
        const std::int32_t count = tree->pixel_start[p + 1] - tree->pixel_start[p];
        tree->prunable = tree->prunable && count <= 255;
        tree->nodes_at[p] = std::uint8_t(std::min(count, 255));
    }
    return tree;
}

}  // namespace

std::shared_ptr<const RayTree> ray_tree(int a, int b, int k) {
    static BoundedCache<std::tuple<int, int, int>, RayTree> cache(ray_tree_cache_budget);
    return cache.get({a, b, k}, [&] { return build_ray_tree(a, b, k); }, [](const RayTree& t) {
        return vector_bytes(t.dx) + vector_bytes(t.dy) + vector_bytes(t.end) + vector_bytes(t.offset) +
               vector_bytes(t.depth) + vector_bytes(t.pixel_start) + vector_bytes(t.pixel_nodes) + vector_bytes(t.nodes_at);
    });
}

}  // namespace isolux
