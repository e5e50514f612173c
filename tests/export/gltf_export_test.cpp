// radrecon export's glTF read back by an independent reader (assimp's glTF 2.0 importer, its PNG
// decoded by libpng): the geometry is the scene's, and the lightmap texel at any texture
// coordinate holds the tone-mapped radiosity of the surface point that coordinate maps to (as a
// viewer maps it: linearly over each triangle), for radiosity that is a known linear function of
// the floor's metric coordinates (s, t) (which thin-plate reconstructs exactly), on a trapezoid,
// where the viewer's mapping and the surface's bilinear parameters differ.

#include <gtest/gtest.h>

#include <assimp/Importer.hpp>
#include <assimp/scene.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/image.h"
#include "export/gltf.h"
#include "export/lightmap.h"
#include "solver/solve.h"
#include "support/png_decode.h"

namespace radrecon {
namespace gltf_export_test {

/// A trapezoidal floor (2 m wide at y = 0, 1 m at y = 1; u along x, v along y, facing +z) under a
/// square lamp facing down.
/// A grey quad named `name` and a square lamp of 10 W/m^2 above it, facing down.
Scene lit_quad(const std::string& name, const std::array<Vec3, 4>& corners, const std::array<Vec3, 4>& lamp_corners) {
  Scene scene;
  scene.name = name + "-and-lamp";
  Surface quad;
  quad.name = name;
  quad.corners = corners;
  quad.reflectance = Rgb(0.5, 0.5, 0.5);
  Surface lamp;
  lamp.name = "lamp";
  lamp.corners = lamp_corners;
  lamp.emission_w_m2 = Rgb(10, 10, 10);
  scene.surfaces = {quad, lamp};
  return scene;
}

Scene floor_and_lamp() {
  return lit_quad("floor", {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(1.5, 1, 0), Vec3(0.5, 1, 0)},
                  {Vec3(0.8, 0.3, 1), Vec3(0.8, 0.7, 1), Vec3(1.2, 0.7, 1), Vec3(1.2, 0.3, 1)});
}

/// The radiosity the floor is given: linear in its (s, t) metres, different per channel, W/m^2.
Rgb floor_radiosity(const Vec2& st) {
  const double f = 0.2 + 1.2 * st.x() + 0.5 * st.y();
  return Rgb(f, 0.5 * f, 0.25 * f + 0.1);
}

/// The scene solved on grid:16, its floor given floor_radiosity() at its elements' centroids.
Solution floor_solution(const Scene& scene) {
  Solution solution = solve_scene(scene, "grid:16", SolveSettings{}, "mesh");
  for (SurfaceSolution& side : solution.surfaces)
    if (side.name == "floor")
      for (SolutionElement& e : side.elements) e.radiosity_w_m2 = floor_radiosity(side.centroid_st(e));
  return solution;
}

TEST(GltfExport, GeometryAndTexelsReadBackByAssimp) {
  const Scene scene = floor_and_lamp();
  const Solution solution = floor_solution(scene);
  const SolutionReconstruction recon(scene, solution, Method::thin_plate, {}, "test");
  const LightmapAtlas atlas = bake_lightmaps(scene, solution, recon, 36, "test");
  const double white = 2.8;  // above the floor's largest value, 2.7: nothing clips there
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "radrecon_gltf_export_test.glb";
  write_lightmapped_glb(path, scene, solution, atlas, white, nlohmann::json::object());

  Assimp::Importer importer;
  const aiScene* read = importer.ReadFile(path.string(), 0);
  ASSERT_NE(read, nullptr) << importer.GetErrorString();
  ASSERT_EQ(read->mNumMeshes, 2u);
  ASSERT_EQ(read->mNumTextures, 1u);
  const aiTexture* texture = read->mTextures[0];
  ASSERT_EQ(texture->mHeight, 0u);  // compressed: the PNG's bytes
  const testing_support::Png image = testing_support::decode_png(reinterpret_cast<const std::uint8_t*>(texture->pcData), texture->mWidth);
  EXPECT_EQ(image.width, atlas.radiosity_w_m2.width());
  EXPECT_EQ(image.height, atlas.radiosity_w_m2.height());

  const aiMesh* floor = nullptr;
  for (unsigned m = 0; m < read->mNumMeshes; ++m)
    if (std::string(read->mMeshes[m]->mName.C_Str()) == "floor") floor = read->mMeshes[m];
  ASSERT_NE(floor, nullptr);
  ASSERT_EQ(floor->mNumVertices, 4u);
  ASSERT_TRUE(floor->HasTextureCoords(0));
  // The corners are the scene's, the normals +z, the faces counter-clockwise seen from +z.
  for (unsigned v = 0; v < 4; ++v) {
    const aiVector3D p = floor->mVertices[v], n = floor->mNormals[v];
    bool corner = false;
    for (const Vec3& c : scene.surfaces[0].corners) corner = corner || (Vec3(p.x, p.y, p.z) - c).norm() < 1e-6;
    EXPECT_TRUE(corner) << "vertex " << v;
    EXPECT_NEAR(n.z, 1.0, 1e-6);
  }
  for (unsigned f = 0; f < floor->mNumFaces; ++f) {
    const aiFace& face = floor->mFaces[f];
    ASSERT_EQ(face.mNumIndices, 3u);
    const aiVector3D a = floor->mVertices[face.mIndices[0]], b = floor->mVertices[face.mIndices[1]],
                     c = floor->mVertices[face.mIndices[2]];
    EXPECT_GT(((b - a) ^ (c - a)).z, 0) << "face " << f;
  }
  // Every texel whose centre maps into the floor: its value against the closed form at the
  // point it maps to (assimp gives glTF texture coordinates as (s, 1 - t): its origin is the
  // image's bottom left).
  int checked = 0, worst = 0;
  for (int iy = 0; iy < image.height; ++iy)
    for (int ix = 0; ix < image.width; ++ix) {
      const double s = (ix + 0.5) / image.width, t = 1.0 - (iy + 0.5) / image.height;
      for (unsigned f = 0; f < floor->mNumFaces; ++f) {
        const aiFace& face = floor->mFaces[f];
        const aiVector3D ta = floor->mTextureCoords[0][face.mIndices[0]], tb = floor->mTextureCoords[0][face.mIndices[1]],
                         tc = floor->mTextureCoords[0][face.mIndices[2]];
        // Barycentric coordinates of (s, t) in the face's texture triangle.
        const double det = (tb.x - ta.x) * (tc.y - ta.y) - (tc.x - ta.x) * (tb.y - ta.y);
        const double l1 = ((s - ta.x) * (tc.y - ta.y) - (tc.x - ta.x) * (t - ta.y)) / det;
        const double l2 = ((tb.x - ta.x) * (t - ta.y) - (s - ta.x) * (tb.y - ta.y)) / det;
        const double l0 = 1 - l1 - l2;
        if (l0 < 0 || l1 < 0 || l2 < 0) continue;
        const auto at = [&](int k) {
          const aiVector3D& v = floor->mVertices[face.mIndices[k]];
          return Vec3(v.x, v.y, v.z);
        };
        const std::optional<Vec2> uv = scene.surfaces[0].parameters(l0 * at(0) + l1 * at(1) + l2 * at(2));
        ASSERT_TRUE(uv.has_value());
        const Rgb expected = floor_radiosity(scene.surfaces[0].frame().st(*uv));
        for (int c = 0; c < 3; ++c) {
          const int want = static_cast<int>(std::lround(255 * srgb_encode(tone_map(expected[c], white))));
          const int got = image.rgb[(static_cast<size_t>(iy) * image.width + ix) * 3 + c];
          worst = std::max(worst, std::abs(got - want));
        }
        ++checked;
        break;
      }
    }
  std::printf("%d texels of the floor checked; largest difference %d of 255\n", checked, worst);
  EXPECT_EQ(checked, atlas.tiles[0].width * atlas.tiles[0].height);
  EXPECT_LE(worst, 1);
  std::filesystem::remove(path);
}

TEST(GltfExport, AModelFarFromTheOriginKeepsItsShapeThroughTheNodesTranslation) {
  // The floor and lamp 300 km along x: as floats there, positions step by 1/32 m (a 0.45 m lamp
  // came out 0.4375 m wide; an outside-in trial). Read back by assimp, each vertex plus its node's
  // translation (a float, exact as export_origin() rounds it) is the scene's corner.
  Scene scene = floor_and_lamp();
  for (Surface& s : scene.surfaces)
    for (Vec3& c : s.corners) c += Vec3(300000.3, -2000.1, 7);
  const Solution solution = floor_solution(scene);
  const SolutionReconstruction recon(scene, solution, Method::thin_plate, {}, "test");
  const LightmapAtlas atlas = bake_lightmaps(scene, solution, recon, 16, "test");
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "radrecon_gltf_far_test.glb";
  write_lightmapped_glb(path, scene, solution, atlas, 2.8, nlohmann::json::object());
  EXPECT_NE(export_origin(scene), Vec3::Zero());
  EXPECT_EQ(export_origin(floor_and_lamp()), Vec3::Zero()) << "a model about the origin keeps its positions";
  // The origin is a float exactly, even where a float's spacing passes the model's extent (a
  // 0.1 m model at x = 6,378,137.3 m, the Earth's radius: 6378137.25 was taken as 6378137).
  for (const double x : {300000.3, 6378137.3, 4.1e7}) {
    Scene far;
    far.surfaces = {scene.surfaces[1]};
    for (Vec3& c : far.surfaces[0].corners) c = Vec3(x, 0, 0) + 0.25 * (c - scene.surfaces[1].corners[0]);
    const Vec3 o = export_origin(far);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(static_cast<double>(static_cast<float>(o[k])), o[k]) << x;
    EXPECT_LT(std::abs(o.x() - x), 8) << x;  // near the model: within a float's spacing there
  }

  Assimp::Importer importer;
  const aiScene* read = importer.ReadFile(path.string(), 0);
  ASSERT_NE(read, nullptr) << importer.GetErrorString();
  int checked = 0;
  for (unsigned k = 0; k < read->mRootNode->mNumChildren; ++k) {
    const aiNode* node = read->mRootNode->mChildren[k];
    ASSERT_EQ(node->mNumMeshes, 1u);
    const aiMesh* mesh = read->mMeshes[node->mMeshes[0]];
    const Surface* surface = nullptr;
    for (const Surface& s : scene.surfaces)
      if (s.name == mesh->mName.C_Str()) surface = &s;
    ASSERT_NE(surface, nullptr) << mesh->mName.C_Str();
    const aiMatrix4x4& m = node->mTransformation;
    const Vec3 translation(m.a4, m.b4, m.c4);
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const Vec3 p = translation + Vec3(mesh->mVertices[v].x, mesh->mVertices[v].y, mesh->mVertices[v].z);
      double nearest = INFINITY;
      for (const Vec3& c : surface->corners) nearest = std::min(nearest, (p - c).norm());
      EXPECT_LT(nearest, 2e-6) << mesh->mName.C_Str() << " vertex " << v;  // 1e-6 of the model's 2 m
      ++checked;
    }
  }
  EXPECT_EQ(checked, 8);
  std::filesystem::remove(path);
}

TEST(GltfExport, SurfacesLyingOnOthersAreRaisedOffThemInTurnAndANeighbourTouchingAnEdgeIsNot) {
  // In one plane, a viewer's depth test draws the lamp or the ceiling's covered part pixel by
  // pixel as the view moves (an outside-in trial: a window in its wall). A 2 m panel lies on the
  // ceiling and a 1 m lamp on the panel: read back by assimp, the panel's corners are the
  // scene's moved 1e-3 of its 2 m along its normal (down, into the room), the lamp's 1e-3 of its
  // 1 m further; the ceiling, and a coplanar tile beside it touching its edge, stay.
  Scene scene;
  scene.name = "room";
  const auto grey = [](const std::string& name, std::array<Vec3, 4> corners, double emission = 0) {
    Surface s;
    s.name = name;
    s.corners = corners;
    s.reflectance = Rgb::Constant(emission > 0 ? 0 : 0.5);
    s.emission_w_m2 = Rgb::Constant(emission);
    return s;
  };
  scene.surfaces = {grey("floor", {Vec3(0, 0, 0), Vec3(3, 0, 0), Vec3(3, 3, 0), Vec3(0, 3, 0)}),
                    grey("ceiling", {Vec3(0, 0, 2), Vec3(0, 3, 2), Vec3(3, 3, 2), Vec3(3, 0, 2)}),
                    grey("beside", {Vec3(3, 0, 2), Vec3(3, 1, 2), Vec3(4, 1, 2), Vec3(4, 0, 2)}),
                    grey("panel", {Vec3(0.5, 0.5, 2), Vec3(0.5, 2.5, 2), Vec3(2.5, 2.5, 2), Vec3(2.5, 0.5, 2)}),
                    grey("lamp", {Vec3(1, 1, 2), Vec3(1, 2, 2), Vec3(2, 2, 2), Vec3(2, 1, 2)}, 10)};
  const double panel_m = 1e-3 * 2, lamp_m = panel_m + 1e-3 * 1;
  EXPECT_EQ(export_raise_m(scene), (std::vector<double>{0, 0, 0, panel_m, lamp_m}));
  const Solution solution = solve_scene(scene, "grid:4", SolveSettings{}, "mesh");
  const SolutionReconstruction recon(scene, solution, Method::constant, {}, "test");
  const LightmapAtlas atlas = bake_lightmaps(scene, solution, recon, 8, "test");
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "radrecon_gltf_raised_test.glb";
  write_lightmapped_glb(path, scene, solution, atlas, 10, nlohmann::json::object());
  Assimp::Importer importer;
  const aiScene* read = importer.ReadFile(path.string(), 0);
  ASSERT_NE(read, nullptr) << importer.GetErrorString();
  int checked = 0;
  for (unsigned k = 0; k < read->mNumMeshes; ++k) {
    const aiMesh* mesh = read->mMeshes[k];
    const std::string name = mesh->mName.C_Str();
    const auto surface = std::find_if(scene.surfaces.begin(), scene.surfaces.end(), [&](const Surface& s) { return s.name == name; });
    ASSERT_NE(surface, scene.surfaces.end()) << name;
    const Vec3 offset = name == "lamp" ? Vec3(0, 0, -lamp_m) : name == "panel" ? Vec3(0, 0, -panel_m) : Vec3::Zero();
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const Vec3 p(mesh->mVertices[v].x, mesh->mVertices[v].y, mesh->mVertices[v].z);
      double nearest = INFINITY;
      for (const Vec3& c : surface->corners) nearest = std::min(nearest, (p - (c + offset)).norm());
      EXPECT_LT(nearest, 1e-6) << name << " vertex " << v;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 20);
  std::filesystem::remove(path);
}

TEST(Lightmap, GuttersRepeatTheirTilesBorderAndTilesDoNotOverlap) {
  // Around each tile, kLightmapGutter texels repeat its border (the nearest texel of the tile),
  // so that bilinear filtering at a tile's edge never reads a neighbour; no texel belongs to two
  // tiles with their gutters. On the floor and lamp of the test above, the floor's texels varying.
  const Scene scene = floor_and_lamp();
  const Solution solution = floor_solution(scene);
  const SolutionReconstruction recon(scene, solution, Method::thin_plate, {}, "test");
  const LightmapAtlas atlas = bake_lightmaps(scene, solution, recon, 36, "test");
  const Image& img = atlas.radiosity_w_m2;
  std::vector<int> owner(static_cast<size_t>(img.width()) * img.height(), -1);
  constexpr int g = kLightmapGutter;
  int gutter_texels = 0;
  for (size_t k = 0; k < atlas.tiles.size(); ++k) {
    const LightmapTile& t = atlas.tiles[k];
    ASSERT_GE(t.x0 - g, 0);
    ASSERT_GE(t.y0 - g, 0);
    ASSERT_LE(t.x0 + t.width + g, img.width());
    ASSERT_LE(t.y0 + t.height + g, img.height());
    for (int y = t.y0 - g; y < t.y0 + t.height + g; ++y)
      for (int x = t.x0 - g; x < t.x0 + t.width + g; ++x) {
        int& o = owner[static_cast<size_t>(y) * img.width() + x];
        EXPECT_EQ(o, -1) << "texel (" << x << ", " << y << ") in tiles " << o << " and " << k;
        o = static_cast<int>(k);
        const int cx = std::clamp(x, t.x0, t.x0 + t.width - 1), cy = std::clamp(y, t.y0, t.y0 + t.height - 1);
        if (cx == x && cy == y) continue;
        ++gutter_texels;
        EXPECT_EQ(img.at(x, y)[0], img.at(cx, cy)[0]) << "gutter texel (" << x << ", " << y << ") of tile " << k;
        EXPECT_EQ(img.at(x, y)[2], img.at(cx, cy)[2]) << "gutter texel (" << x << ", " << y << ") of tile " << k;
      }
  }
  EXPECT_GT(gutter_texels, 100);
  // The floor's border varies along it: a gutter copying one value everywhere would fail above.
  const LightmapTile& floor_tile = atlas.tiles[0].side.surface == 0 ? atlas.tiles[0] : atlas.tiles[1];
  EXPECT_NE(img.at(floor_tile.x0, floor_tile.y0)[0], img.at(floor_tile.x0 + floor_tile.width - 1, floor_tile.y0)[0]);
}

TEST(Lightmap, TheLongestSideGetsExactlyTheTexelsAsked) {
  // length x (texels / longest) rounds up to one more texel at some lengths (12.5 m, 5.56 m):
  // at the largest --texels, 16380, that tile and its gutters would not fit a 16384 texture.
  for (const double length_m : {12.5, 5.56, 1.0}) {
    const Scene scene = lit_quad("strip", {Vec3(0, 0, 0), Vec3(length_m, 0, 0), Vec3(length_m, 0.002, 0), Vec3(0, 0.002, 0)},
                                 {Vec3(0, 0, 1), Vec3(0, 0.001, 1), Vec3(0.001, 0.001, 1), Vec3(0.001, 0, 1)});
    const Solution solution = solve_scene(scene, "grid:2", SolveSettings{}, "mesh");
    const SolutionReconstruction recon(scene, solution, Method::constant, {}, "test");
    for (const int texels : {1000, 16380}) {
      const LightmapAtlas atlas = bake_lightmaps(scene, solution, recon, texels, "test");
      const LightmapTile& tile = atlas.tiles[0].side.surface == 0 ? atlas.tiles[0] : atlas.tiles[1];
      EXPECT_EQ(tile.width, texels) << length_m << " m";
    }
  }
}

TEST(Lightmap, SizeIsTheBakedAtlasAndTheMostThatFitAreFound) {
  // lightmap_size() lays the atlas out without making it (export's memory check): the atlas that
  // bake_lightmaps() then makes has that size. most_lightmap_texels_below(): the most texels
  // whose atlas passes a test, the next failing it.
  const Scene scene = lit_quad("floor", {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(2, 1, 0), Vec3(0, 1, 0)},
                               {Vec3(0.3, 0.3, 1), Vec3(0.3, 0.7, 1), Vec3(0.7, 0.7, 1), Vec3(0.7, 0.3, 1)});
  const Solution solution = solve_scene(scene, "grid:4", SolveSettings{}, "mesh");
  const SolutionReconstruction recon(scene, solution, Method::constant, {}, "test");
  for (const int texels : {2, 31, 100}) {
    const LightmapSize size = lightmap_size(scene, solution, texels, "test");
    const LightmapAtlas atlas = bake_lightmaps(scene, solution, recon, texels, "test");
    EXPECT_EQ(size.width, atlas.radiosity_w_m2.width()) << texels;
    EXPECT_EQ(size.height, atlas.radiosity_w_m2.height()) << texels;
  }
  const double most_texels = 5000;
  const auto fits = [&](LightmapSize s) { return s.texels() <= most_texels; };
  const int most = most_lightmap_texels_below(scene, solution, 1000, fits);
  EXPECT_TRUE(fits(lightmap_size(scene, solution, most, "test")));
  EXPECT_FALSE(fits(lightmap_size(scene, solution, most + 1, "test")));
  EXPECT_EQ(most_lightmap_texels_below(scene, solution, 1000, [](LightmapSize) { return false; }), 1);
}

TEST(Lightmap, CountsTheTexelsWhereTheMethodGivesNoValue) {
  // natural-neighbour with outside=none has no value outside the hull of a side's element centres,
  // here the rectangle of the extreme centres: the count is the texels whose point lies outside it
  // (counted from the tile's geometry), and they hold 0.
  const Scene scene = lit_quad("floor", {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)},
                               {Vec3(0.3, 0.3, 1), Vec3(0.3, 0.7, 1), Vec3(0.7, 0.7, 1), Vec3(0.7, 0.3, 1)});
  const Solution solution = solve_scene(scene, "grid:4", SolveSettings{}, "mesh");
  MethodParams params;
  params.outside = OutsideHull::none;
  const SolutionReconstruction recon(scene, solution, Method::natural_neighbour, params, "test");
  const LightmapAtlas atlas = bake_lightmaps(scene, solution, recon, 30, "test");
  size_t expected = 0, texels = 0;
  for (const LightmapTile& t : atlas.tiles) {
    const SurfaceSolution& side = solution.surfaces[t.solution_side];
    Vec2 low = Vec2::Constant(1e9), high = Vec2::Constant(-1e9);
    for (const SolutionElement& e : side.elements) low = low.cwiseMin(side.centroid_st(e)), high = high.cwiseMax(side.centroid_st(e));
    for (int j = 0; j < t.height; ++j)
      for (int i = 0; i < t.width; ++i) {
        const Vec2 st((i + 0.5) / t.width * side.length_u_m, (j + 0.5) / t.height * side.length_v_m);
        ASSERT_FALSE(st.x() == low.x() || st.x() == high.x() || st.y() == low.y() || st.y() == high.y());
        const bool outside = (st.array() < low.array()).any() || (st.array() > high.array()).any();
        expected += outside;
        ++texels;
        if (outside) EXPECT_EQ(atlas.radiosity_w_m2.at(t.x0 + i, t.y0 + j)[0], 0.0);
      }
  }
  EXPECT_EQ(atlas.texels, texels);
  EXPECT_GT(expected, 100u);
  EXPECT_EQ(atlas.texels_without_value, expected);
}

}  // namespace gltf_export_test
}  // namespace radrecon
