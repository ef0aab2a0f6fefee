// Beyond the paper: sprite pixels shaded by the way their surface faces each
// light (Params::sprite_shading). The paper lights a sprite pixel flat: a
// crown's side turned away from a lamp gets what its side facing it gets.
// Here each sprite pixel has a normal and the 3D point it shows (the ground
// frame of solid.hpp), and a light's value there is multiplied by
//   (1 - s) + s * max(0, n . (light - point) / |light - point|)
// (Lambert's cosine; s = shading_strength), the light standing at its
// height over its centre. Ground pixels are not shaded.
//
// Where the normals come from (sprite_normals):
//   solids:    the estimated solids' own normals at the points they show
//              (EstimatedObject::normal_at, solid_estimate.hpp); a pixel no
//              solid shows takes its nearest shown neighbour's that one does;
//   shapes:    the manifest's shapes (the nearest solid's normal, as the 3D
//              reference takes it), else its height map differenced;
//   luminance: the picture's brightness gradient, as normal-map generators
//              make them: brightness read as relief, luminance_relief pixels
//              of height from black to white, on the screen's plane.
// The point a pixel shows is the shapes' (shapes) or the estimated solids'
// (solids, luminance: so that the sources differ in their normals alone).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include <glm/geometric.hpp>

#include "isolux/light_trace.hpp"
#include "isolux/params.hpp"
#include "isolux/solid.hpp"
#include "isolux/truth.hpp"
#include "isolux/world.hpp"

namespace isolux {

struct SolidsCache;
struct SpriteSolids;

// Pixels of height from black to white when brightness is read as relief
// (sprite_shading luminance): the slope a normal-map generator gives a
// sprite's shading at its default strength.
inline constexpr double luminance_relief = 8;

// One sprite's normals and the heights of the points its pixels show, by
// sprite pixel (row by row). Where the sprite shows nothing (transparent at
// its threshold) the normal is (0, 0, 0) and the height 0.
struct SpriteNormals {
    int width = 0, height = 0;
    std::vector<Vec3> normal;    // unit, ground frame
    std::vector<float> heights;  // pixels above the ground
    bool empty() const { return normal.empty(); }
};

// The normals of tileset sprite `s` from `from` (not none) under preset `p`
// (its opacity threshold and, for solids and luminance, the estimate's
// parameters: `estimate`, the sprite's solids under `p`, when the caller
// has them, else they are estimated here). Throws Error naming the tileset
// and the sprite when `from` is shapes and the sprite has neither a shape
// nor a height map.
SpriteNormals sprite_normals(const Tileset& tileset, const Sprite& s, const Params& p, SpriteShading from,
                             const SpriteSolids* estimate = nullptr);

// The normals of the height field a w x h sprite's `shown` pixels show
// (`heights` per pixel): the cross product of the 3D points' differences
// along x and y, each the central one where both neighbours are shown and
// bend alike, else the one-sided one with the smaller rise (a silhouette or
// the edge between two objects is not a slope). A pixel with no shown
// neighbour along an axis takes no slope along it.
std::vector<Vec3> normals_from_heights(const Mask& shown, const std::vector<float>& heights);

// The ground frame's unit vectors of the screen's tangent space: +X right,
// +Y up, +Z toward the viewer (the view line is X = Y = Z + const).
inline const Vec3 screen_right{0.70710678118654752, -0.70710678118654752, 0};
inline const Vec3 screen_up{-0.40824829046386302, -0.40824829046386302, 0.81649658092772603};
inline const Vec3 toward_viewer{0.57735026918962576, 0.57735026918962576, 0.57735026918962576};
// A ground-frame normal in the screen's tangent space, and back.
inline Vec3 to_screen_tangent(Vec3 n) { return {glm::dot(n, screen_right), glm::dot(n, screen_up), glm::dot(n, toward_viewer)}; }
inline Vec3 from_screen_tangent(Vec3 t) { return t.x * screen_right + t.y * screen_up + t.z * toward_viewer; }

// How a normal map's green channel points: opengl, +Y up the screen (Godot,
// Blender); directx, +Y down (Unity's and Unreal's importers flip it).
enum class NormalConvention { opengl, directx };
// The sprite's normals as an 8-bit RGB normal map in the screen's tangent
// space (+X right, +Y up or down by `convention`, +Z toward the viewer),
// each component c as round((c + 1) / 2 * 255); pixels the sprite does not
// show are flat, (128, 128, 255). 3 bytes a pixel, row by row.
std::vector<std::uint8_t> normal_map_rgb(const SpriteNormals& n, NormalConvention convention);
// One ground-frame unit normal as a normal map's colour (as normal_map_rgb).
std::array<std::uint8_t, 3> normal_map_colour(Vec3 n, NormalConvention convention = NormalConvention::opengl);
// The heights of the points the sprite shows, rounded to whole pixels (the
// manifest's height_map format: 16-bit grey, pixels above the ground).
std::vector<std::uint16_t> height_map_values(const SpriteNormals& n);

// Whether `p` shades sprite pixels at all (a source, and a strength above 0).
inline bool shades_sprites(const Params& p) { return p.sprite_shading != SpriteShading::none && p.shading_strength > 0; }

// Lambert's cosine between unit normal `n` at `point` and the direction to
// `light`, at least 0 (1 where the light stands at the point).
double lambert(Vec3 n, Vec3 point, Vec3 light);

// Per world pixel of `rect`: whether it shows a sprite, the normal there
// (ground frame, each component times 127, rounded; (0, 0, 0) on the ground)
// and the height of the point it shows.
struct ShadingMap {
    Rect rect;
    std::vector<std::array<std::int8_t, 3>> normal;
    std::vector<float> height;
    bool empty() const { return normal.empty(); }
};

// Each sprite's normals, made once (they depend on the sprite, the source
// and the parameters only). The owner empties it when any of them changes.
struct NormalsCache {
    SpriteShading from = SpriteShading::none;
    std::vector<SpriteNormals> sprites;
    std::vector<char> made;
    void clear() { sprites.clear(), made.clear(); }
};
// Sprite `index`'s normals from `p.sprite_shading`, made into `cache` when
// missing; from the estimates in `solids` (made there when missing) when
// given, so that a frame tracing against solids estimates each sprite once.
const SpriteNormals& cached_normals(NormalsCache& cache, const World& world, std::size_t index, const Params& p,
                                    SolidsCache* solids = nullptr);

// The shading map of `region` from `p.sprite_shading` (not none): the
// topmost overlay each pixel shows, as the 3D reference finds it, and its
// normals. Error as sprite_normals (shapes) for an overlay meeting the region.
ShadingMap build_shading_map(const World& world, const Params& p, Rect region, NormalsCache& cache,
                             SolidsCache* solids = nullptr);

// Multiplies each lit sprite pixel of `mask` (value > 0, inside `map`) by
// its shading factor for the light at the mask's centre, `light_height`
// above the ground, rounded to the nearest byte (in single precision, the
// map's normal taken as stored, its components / 127). With
// sprite_shading none or shading_strength 0, nothing changes.
void shade_sprites(LightMask& mask, const ShadingMap& map, double light_height, const Params& p);

}  // namespace isolux
