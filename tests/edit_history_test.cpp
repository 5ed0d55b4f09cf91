// Undo and redo of parameter edits (app/config/edit_history.h): exact restoration, the camera left
// alone, redo dropped by a new edit, the history's bound.
#include "app/config/edit_history.h"

#include <gtest/gtest.h>

#include "app/config/params.h"

namespace tallow::app {
namespace {

constexpr const char* kCsv =
    "name,source,sigma_s_r,sigma_s_g,sigma_s_b,sigma_a_r,sigma_a_g,sigma_a_b,g_r,g_g,g_b,eta,unit\n"
    "Marble,Jensen et al. 2001,2.19,2.62,3,0.0021,0.0041,0.0071,0,0,0,1.5,mm^-1\n"
    "Ketchup,Jensen et al. 2001,0.18,0.07,0.03,0.061,0.97,1.45,0,0,0,1.3,mm^-1\n";

class EditHistoryTest : public ::testing::Test {
 protected:
  EditHistoryTest() : table(sss::MaterialTable::parse(kCsv, "inline.csv")), registry(parameterRegistry(table)) {
    registry.applyDefaults(config);
    sss::SceneObject object;
    object.translucent = true;
    object.material = *table.find("Marble");
    config.scene.objects.push_back(object);
    config.scene.camera.position = {0.0f, 0.1f, 0.3f};
  }
  nlohmann::json values(const Config& c) const { return registry.snapshot(c); }

  sss::MaterialTable table;
  Registry registry;
  Config config;
};

TEST_F(EditHistoryTest, UndoRestoresEveryValueExactlyAndRedoReappliesThem) {
  const nlohmann::json start = values(config);
  EditHistory history(registry, config);
  EXPECT_FALSE(history.canUndo());
  EXPECT_FALSE(history.commit(config)) << "nothing changed: no step";

  registry.set(config, "sss.maps", 8);
  EXPECT_TRUE(history.commit(config));
  EXPECT_EQ(history.undoLabel(), "sss.maps auto → 8");
  // A material picked and then edited: name and coefficients change together (two steps).
  registry.set(config, "material", "Ketchup");
  ASSERT_TRUE(history.commit(config));
  registry.set(config, "material.eta", 1.4);
  ASSERT_TRUE(history.commit(config));
  EXPECT_EQ(registry.get(config, "material"), "Ketchup (modified)");
  EXPECT_EQ(history.undoLabel(), "material.eta 1.3 → 1.4") << "the name's mark is the edit's consequence";
  const nlohmann::json edited = values(config);

  for (int i = 0; i < 3; ++i) config = *history.undo(config);
  EXPECT_EQ(values(config), start) << "three undos: back to the start, to the bit";
  EXPECT_FALSE(history.undo(config).has_value());
  for (int i = 0; i < 3; ++i) config = *history.redo(config);
  EXPECT_EQ(values(config), edited);
  EXPECT_FALSE(history.redo(config).has_value());
}

TEST_F(EditHistoryTest, TheCameraIsNavigationNotAnEdit) {
  EditHistory history(registry, config);
  registry.set(config, "sss.samples", 3);
  history.commit(config);
  registry.set(config, "camera.position", nlohmann::json::array({1.0, 2.0, 3.0}));
  EXPECT_FALSE(history.commit(config)) << "a camera move makes no step";
  config = *history.undo(config);
  EXPECT_EQ(registry.get(config, "sss.samples"), *registry.find("sss.samples")->defaultValue);
  EXPECT_EQ(config.scene.camera.position, glm::vec3(1.0f, 2.0f, 3.0f)) << "undo keeps the camera where it is";
}

TEST_F(EditHistoryTest, ANewEditDropsTheRedoAndTheOldestStepsGo) {
  EditHistory history(registry, config);
  registry.set(config, "sss.maps", 4);
  history.commit(config);
  config = *history.undo(config);
  EXPECT_TRUE(history.canRedo());
  registry.set(config, "sss.maps", 5);
  history.commit(config);
  EXPECT_FALSE(history.canRedo()) << "a new edit after an undo forgets what could be redone";
  for (int i = 0; i < static_cast<int>(EditHistory::kMaxSteps) + 10; ++i) {
    registry.set(config, "sss.samples", 1 + i % 2);
    history.commit(config);
  }
  int undos = 0;
  while (history.canUndo()) {
    config = *history.undo(config);
    ++undos;
  }
  EXPECT_EQ(undos, static_cast<int>(EditHistory::kMaxSteps));
}

}  // namespace
}  // namespace tallow::app
