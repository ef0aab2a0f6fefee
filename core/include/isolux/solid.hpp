// Simple solids (box, cylinder, cone, ellipsoid): the true 3D shapes behind a
// sprite, as a game's collision shapes describe them. Not in the paper: the
// paper estimates geometry from alpha alone; these are what the estimate is
// measured against (docs/accuracy.md).
//
// Coordinates are pixels in the isometric ground frame of the default
// tileset's projection: X and Y on the ground, Z up, and
//   screen x = X - Y,   screen y = (X + Y) / 2 - Z.
// A sprite's solids are relative to its anchor (the ground point it stands
// on); world solids are relative to the world's screen origin.
#pragma once
#include <array>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

namespace isolux {

enum class SolidKind { box, cylinder, cone, ellipsoid };
std::string_view to_string(SolidKind k);

// A point or direction in the ground frame, pixels (GLM, double precision:
// the 3D reference tests segments against solids hundreds of pixels long).
using Vec3 = glm::dvec3;

struct Solid {
    SolidKind kind = SolidKind::box;
    Vec3 a{0.0};  // box: min corner; cylinder and cone: centre of the base; ellipsoid: centre
    Vec3 b{0.0};  // box: max corner; cylinder and cone: (radius, radius, height); ellipsoid: radii
    friend bool operator==(const Solid&, const Solid&) = default;
};

// The 3D point of screen position (sx, sy) at height z above the ground.
Vec3 ground_frame(double sx, double sy, double z);

// The solid moved by `by`.
Solid translated(const Solid& s, Vec3 by);

// Whether the solid encloses any volume (a zero-size solid casts nothing).
bool has_volume(const Solid& s);

// Whether `p` lies inside the solid (its boundary included).
bool solid_contains(const Solid& s, Vec3 p);

// Whether the segment from `from` to `to`, up to the fraction `t_end` of its
// length (0..1), passes through the solid.
bool segment_hits(const Solid& s, Vec3 from, Vec3 to, double t_end);

// The outward unit normal of the solid's surface nearest `p`, and how far `p`
// is from that surface (approximately, pixels).
Vec3 solid_normal(const Solid& s, Vec3 p, double* distance = nullptr);

// The height of the topmost solid surface seen at screen offset (sx, sy) from
// the solids' origin (along the view line, X = Y = Z + const), or none when the
// line meets none (-infinity): the visible surface a height map records. It
// may lie below the ground: solids are not cut by it.
double surface_height(const std::vector<Solid>& solids, double sx, double sy);

// The axis-aligned box around the solid: min and max corners.
std::array<Vec3, 2> solid_bounds(const Solid& s);

// The screen rectangle (x = X - Y, y = (X + Y) / 2, whole pixels) of the
// ground under the solid, with a pixel of margin: its x, y, width, height.
// What tracing against shapes fills, and what a manifest's shape may cover.
std::array<long long, 4> ground_box(const Solid& s);

}  // namespace isolux
