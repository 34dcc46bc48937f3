// The field factory: a file becomes the right kind of field, with the extras its users need
// (an analytic scene's integrator, a trained model's own placement), and anything else is an
// InputError naming the setting.
#include <gtest/gtest.h>

#include "core/output_file.h"
#include "expect_input_error.h"
#include "field_files/field_factory.h"
#include "radiance/grid_io.h"
#include "scene/analytic_scene.h"
#include "scratch_dir.h"

using namespace inim;

namespace {
ScratchDir scratch("field_factory");

std::string saveModel(const std::string& name, const std::string& metadata) {
  VoxelGrid g = VoxelGrid::create(Point3(-1.0f), Point3(1.0f), glm::ivec3(4), 0, DensityActivation::Softplus,
                                  Vec3(0.0f), 0.05f);
  g.metadata = metadata;
  const std::string path = scratch.path(name);
  saveVoxelGrid(g, path);
  return path;
}
}  // namespace

TEST(FieldFactory, SceneJsonIsAnAnalyticSceneInMillimetres) {
  LoadedField f = loadField(defaultScenePath(), "scene");
  ASSERT_TRUE(f.field);
  EXPECT_EQ(f.kind, FieldKind::AnalyticScene);
  EXPECT_EQ(f.analyticScene, f.field.get());  // the same object, with its integrator interface
  EXPECT_FALSE(f.placement);                 // already in display millimetres
  EXPECT_EQ(f.field->encoding(), FieldEncoding::Spectral);
  EXPECT_STREQ(fieldKindName(f.kind), "analytic scene");
}

TEST(FieldFactory, ModelCarriesThePlacementOfItsUnits) {
  // A model of another dataset is in that dataset's units: placed at the paper's 0.0075
  // field units per mm, i.e. 133.3 mm per unit.
  LoadedField f = loadField(saveModel("nerf.inimrf", R"({"units": "dataset"})"), "field");
  EXPECT_EQ(f.kind, FieldKind::RadianceField);
  EXPECT_EQ(f.analyticScene, nullptr);
  EXPECT_EQ(f.field->encoding(), FieldEncoding::RGB);
  ASSERT_TRUE(f.placement);
  EXPECT_NEAR(f.placement->scale.x, 1.0 / 0.0075, 1e-9);
  // An inim capture is in millimetres: scale 1.
  LoadedField mm = loadField(saveModel("MM.INIMRF", R"({"units": "mm"})"), "field");  // extension in any case
  ASSERT_TRUE(mm.placement);
  EXPECT_EQ(mm.placement->scale, Vec3d(1.0));
}

TEST(FieldFactory, OtherExtensionsNameTheSetting) {
  const InputError e = expectInputError([] { (void)loadField("model.obj", "field_model"); });
  EXPECT_EQ(e.key(), "field_model");
  EXPECT_EQ(e.file(), "");
  EXPECT_NE(e.value().find("model.obj"), std::string::npos);
}

TEST(FieldFactory, SplatFilesAreGaussianSplatsInDisplayMillimetres) {
  LoadedField f = loadField(dataPath("scenes/splats/guitar.compressed.ply"), "field");
  EXPECT_EQ(f.kind, FieldKind::GaussianSplats);
  EXPECT_STREQ(fieldKindName(f.kind), "Gaussian splats");
  EXPECT_FALSE(f.placement);  // placed on load
  EXPECT_EQ(f.field->encoding(), FieldEncoding::RGB);
  Point3 lo, hi;
  f.field->bounds(lo, hi);
  EXPECT_LT(lo.x, 0.0f);  // straddles the panel centre
  EXPECT_GT(hi.x, 0.0f);
  const LoadedField s = loadField(std::string(INIM_SOURCE_DATA_DIR) + "/tests/data/splats/metalsplatter-3pts.splat", "field");
  EXPECT_EQ(s.kind, FieldKind::GaussianSplats);
  // A broken splat file names the file, not the setting.
  const InputError e = expectInputError([] { (void)loadField("no-such.ply", "field"); });
  EXPECT_EQ(e.file(), "no-such.ply");
}
