// Segment tests and normals for the simple solids of solid.hpp. Each solid is
// convex, so a line meets it in one interval: the candidates where the line
// crosses a bounding surface are sorted and the pieces between them tested
// at their midpoints.
#include "isolux/solid.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

namespace isolux {

namespace {

Vec3 add(Vec3 a, Vec3 b) { return a + b; }
Vec3 sub(Vec3 a, Vec3 b) { return a - b; }
Vec3 mul(Vec3 a, double s) { return a * s; }
double dot(Vec3 a, Vec3 b) { return glm::dot(a, b); }
// A zero vector points up (glm::normalize would give NaNs).
Vec3 unit(Vec3 a) {
    const double l = glm::length(a);
    return l > 0 ? a * (1 / l) : Vec3{0, 0, 1};
}

// Roots of a t^2 + b t + c = 0, appended when real.
void roots(double a, double b, double c, std::vector<double>& out) {
    if (std::abs(a) < 1e-12) {
        if (std::abs(b) > 1e-12) out.push_back(-c / b);
        return;
    }
    const double disc = b * b - 4 * a * c;
    if (disc < 0) return;
    const double s = std::sqrt(disc);
    out.push_back((-b - s) / (2 * a));
    out.push_back((-b + s) / (2 * a));
}

// Where o + t d crosses the planes v = lo and v = hi along one axis.
void slab(double o, double d, double lo, double hi, std::vector<double>& out) {
    if (std::abs(d) < 1e-12) return;
    out.push_back((lo - o) / d);
    out.push_back((hi - o) / d);
}

void crossings(const Solid& s, Vec3 o, Vec3 d, std::vector<double>& t) {
    switch (s.kind) {
        case SolidKind::box:
            slab(o.x, d.x, s.a.x, s.b.x, t);
            slab(o.y, d.y, s.a.y, s.b.y, t);
            slab(o.z, d.z, s.a.z, s.b.z, t);
            break;
        case SolidKind::ellipsoid: {
            const Vec3 q{(o.x - s.a.x) / s.b.x, (o.y - s.a.y) / s.b.y, (o.z - s.a.z) / s.b.z};
            const Vec3 e{d.x / s.b.x, d.y / s.b.y, d.z / s.b.z};
            roots(dot(e, e), 2 * dot(q, e), dot(q, q) - 1, t);
            break;
        }
        case SolidKind::cylinder: {
            const double qx = o.x - s.a.x, qy = o.y - s.a.y, r = s.b.x;
            roots(d.x * d.x + d.y * d.y, 2 * (qx * d.x + qy * d.y), qx * qx + qy * qy - r * r, t);
            slab(o.z, d.z, s.a.z, s.a.z + s.b.z, t);
            break;
        }
        case SolidKind::cone: {
            // x^2 + y^2 = k^2 (apex - z)^2, the double cone; the slab keeps the lower nappe's part.
            const double qx = o.x - s.a.x, qy = o.y - s.a.y, apex = s.a.z + s.b.z;
            const double k = s.b.z > 0 ? s.b.x / s.b.z : 0, qz = apex - o.z;
            roots(d.x * d.x + d.y * d.y - k * k * d.z * d.z, 2 * (qx * d.x + qy * d.y + k * k * qz * d.z),
                  qx * qx + qy * qy - k * k * qz * qz, t);
            slab(o.z, d.z, s.a.z, apex, t);
            break;
        }
    }
}

}  // namespace

std::string_view to_string(SolidKind k) {
    switch (k) {
        case SolidKind::box: return "box";
        case SolidKind::cylinder: return "cylinder";
        case SolidKind::cone: return "cone";
        case SolidKind::ellipsoid: return "ellipsoid";
    }
    return "box";
}

Vec3 ground_frame(double sx, double sy, double z) {
    // Inverts screen x = X - Y, screen y = (X + Y) / 2 - Z.
    return {sy + z + sx / 2, sy + z - sx / 2, z};
}

Solid translated(const Solid& s, Vec3 by) {
    Solid t = s;
    t.a = add(s.a, by);
    if (s.kind == SolidKind::box) t.b = add(s.b, by);
    return t;
}

bool solid_contains(const Solid& s, Vec3 p) {
    switch (s.kind) {
        case SolidKind::box:
            return p.x >= s.a.x && p.x <= s.b.x && p.y >= s.a.y && p.y <= s.b.y && p.z >= s.a.z && p.z <= s.b.z;
        case SolidKind::ellipsoid: {
            const Vec3 q{(p.x - s.a.x) / s.b.x, (p.y - s.a.y) / s.b.y, (p.z - s.a.z) / s.b.z};
            return dot(q, q) <= 1;
        }
        case SolidKind::cylinder: {
            const double dx = p.x - s.a.x, dy = p.y - s.a.y;
            return p.z >= s.a.z && p.z <= s.a.z + s.b.z && dx * dx + dy * dy <= s.b.x * s.b.x;
        }
        case SolidKind::cone: {
            const double dx = p.x - s.a.x, dy = p.y - s.a.y, apex = s.a.z + s.b.z;
            if (p.z < s.a.z || p.z > apex || s.b.z <= 0) return false;
            const double r = s.b.x * (apex - p.z) / s.b.z;
            return dx * dx + dy * dy <= r * r;
        }
    }
    return false;
}

bool has_volume(const Solid& s) {
    switch (s.kind) {
        case SolidKind::box: return s.b.x > s.a.x && s.b.y > s.a.y && s.b.z > s.a.z;
        case SolidKind::ellipsoid: return s.b.x > 0 && s.b.y > 0 && s.b.z > 0;
        case SolidKind::cylinder:
        case SolidKind::cone: return s.b.x > 0 && s.b.z > 0;
    }
    return false;
}

bool segment_hits(const Solid& s, Vec3 from, Vec3 to, double t_end) {
    if (!has_volume(s)) return false;  // a solid of zero size casts nothing
    const Vec3 d = sub(to, from);
    std::vector<double> t = {0.0, t_end};
    crossings(s, from, d, t);
    std::sort(t.begin(), t.end());
    for (std::size_t i = 0; i + 1 < t.size(); ++i) {
        const double t0 = std::max(0.0, t[i]), t1 = std::min(t_end, t[i + 1]);
        if (!(t1 > t0)) continue;
        if (solid_contains(s, add(from, mul(d, (t0 + t1) / 2)))) return true;
    }
    return false;
}

Vec3 solid_normal(const Solid& s, Vec3 p, double* distance) {
    double dist = 0;
    Vec3 n{0, 0, 1};
    switch (s.kind) {
        case SolidKind::box: {
            const double faces[6] = {p.x - s.a.x, s.b.x - p.x, p.y - s.a.y, s.b.y - p.y, p.z - s.a.z, s.b.z - p.z};
            const Vec3 normals[6] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
            int best = 0;
            for (int i = 1; i < 6; ++i)
                if (std::abs(faces[i]) < std::abs(faces[best])) best = i;
            n = normals[best];
            dist = std::abs(faces[best]);
            break;
        }
        case SolidKind::ellipsoid: {
            const Vec3 q = sub(p, s.a);
            n = unit({q.x / (s.b.x * s.b.x), q.y / (s.b.y * s.b.y), q.z / (s.b.z * s.b.z)});
            const Vec3 u{q.x / s.b.x, q.y / s.b.y, q.z / s.b.z};
            dist = std::abs(std::sqrt(dot(u, u)) - 1) * std::min({s.b.x, s.b.y, s.b.z});
            break;
        }
        case SolidKind::cylinder: {
            const double dx = p.x - s.a.x, dy = p.y - s.a.y, rr = std::sqrt(dx * dx + dy * dy);
            const double side = std::abs(rr - s.b.x), top = std::abs(s.a.z + s.b.z - p.z);
            if (top < side) {
                n = {0, 0, 1};
                dist = top;
            } else {
                n = rr > 0 ? Vec3{dx / rr, dy / rr, 0} : Vec3{0, 0, 1};
                dist = side;
            }
            break;
        }
        case SolidKind::cone: {
            const double dx = p.x - s.a.x, dy = p.y - s.a.y, rr = std::sqrt(dx * dx + dy * dy);
            const double k = s.b.z > 0 ? s.b.x / s.b.z : 0, apex = s.a.z + s.b.z;
            n = rr > 0 ? unit({dx / rr, dy / rr, k}) : Vec3{0, 0, 1};
            dist = std::abs(rr - k * (apex - p.z)) / std::sqrt(1 + k * k);
            break;
        }
    }
    if (distance) *distance = dist;
    return n;
}

double surface_height(const std::vector<Solid>& solids, double sx, double sy) {
    // Points of the view line: ground_frame(sx, sy, z) = o + z (1, 1, 1).
    const Vec3 o = ground_frame(sx, sy, 0), d{1, 1, 1};
    double best = -HUGE_VAL;
    std::vector<double> t;
    for (const Solid& s : solids) {
        if (!has_volume(s)) continue;
        t.clear();
        crossings(s, o, d, t);
        std::sort(t.begin(), t.end());
        for (std::size_t i = t.size(); i-- > 1;) {
            if (!(t[i] > t[i - 1]) || t[i] <= best) continue;
            if (solid_contains(s, add(o, mul(d, (t[i] + t[i - 1]) / 2)))) {
                best = std::max(best, t[i]);
                break;
            }
        }
    }
    return best;
}

std::array<Vec3, 2> solid_bounds(const Solid& s) {
    switch (s.kind) {
        case SolidKind::box: return {s.a, s.b};
        case SolidKind::ellipsoid: return {sub(s.a, s.b), add(s.a, s.b)};
        case SolidKind::cylinder:
        case SolidKind::cone:
            return {Vec3{s.a.x - s.b.x, s.a.y - s.b.x, s.a.z}, Vec3{s.a.x + s.b.x, s.a.y + s.b.x, s.a.z + s.b.z}};
    }
    return {s.a, s.b};
}

std::array<long long, 4> ground_box(const Solid& s) {
    const auto b = solid_bounds(s);
    return {(long long)std::floor(b[0].x - b[1].y) - 1, (long long)std::floor((b[0].x + b[0].y) / 2) - 1,
            (long long)std::ceil((b[1].x - b[0].y) - (b[0].x - b[1].y)) + 3,
            (long long)std::ceil((b[1].x + b[1].y - b[0].x - b[0].y) / 2) + 3};
}

}  // namespace isolux
