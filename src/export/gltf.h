#pragma once
// Baked lighting out: a solved scene as binary glTF 2.0 (.glb) with its reconstructed radiosity
// as a lightmap texture (export/lightmap.h), for Blender, three.js and game engines.
//
// Each surface side is a mesh of its own (named after the side; a two-sided surface gives two,
// facing opposite ways) with positions (metres, the scene's axes, from export_origin()), normals
// and TEXCOORD_0 into the atlas. They share one material: black base colour, fully rough, not metallic, and the
// lightmap as its emissive texture (emissiveFactor 1), so that any glTF viewer shows the baked
// radiosity as it is, unlit by its own lights. The lightmap is an sRGB PNG of
// clamp(B / white, 0, 1) per channel (core/image.h's tone mapping: B the radiosity in W/m^2,
// white the radiosity shown as white), sampled with linear filtering and clamped at the edges.
// asset.extras records the method, the white point (W/m^2) and the density (texels per metre).

#include <filesystem>
#include <vector>
#include <nlohmann/json_fwd.hpp>

#include "export/lightmap.h"

namespace radrecon {

/// Where a model's exported positions are measured from, metres: (0, 0, 0) for a model within
/// tol::kExportOriginFreeExtents of its extent from it (the usual case); else its bounding box's
/// centre rounded to a multiple of a power of two at least its extent and at least a float's
/// spacing there (so a float exactly), which every node then takes as its translation (float
/// positions far from (0, 0, 0) would lose the model's shape).
Vec3 export_origin(const Scene& scene);

/// By scene surface: how far its exported mesh is raised, each side along its own normal,
/// metres: for a surface covering part of another (solver/covered.h: a lamp lying on a ceiling, a
/// window in a wall, a rug on a floor), tol::kExportRaisedRelative of its longer side above the
/// highest raise of those it covers (a canvas on a frame on a wall stands above both); else 0.
/// In the same plane, a viewer's depth test would draw one or the other pixel by pixel as the
/// view moves (the lamp over the ceiling's dark covered part: a flicker, an outside-in trial).
std::vector<double> export_raise_m(const Scene& scene);

/// Writes `path` atomically. `extras` goes into asset.extras (with white_w_m2 and
/// texels_per_metre added).
void write_lightmapped_glb(const std::filesystem::path& path, const Scene& scene, const Solution& solution,
                           const LightmapAtlas& atlas, double white_w_m2, const nlohmann::json& extras);

}  // namespace radrecon
