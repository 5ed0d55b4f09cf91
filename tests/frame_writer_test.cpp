// The capture's writer thread (app/commands/frame_writer.h): jobs in order, on another thread, a
// failure reported to the render thread and nothing written after it.
#include <gtest/gtest.h>

#include <stdexcept>
#include <thread>
#include <vector>

#include "app/commands/frame_writer.h"

namespace tallow {
namespace {

TEST(FrameWriter, RunsJobsInOrderOnItsOwnThread) {
  std::vector<int> done;
  std::thread::id worker;
  {
    app::FrameWriter writer(1);
    for (int i = 0; i < 20; ++i)
      writer.submit([&, i] {
        done.push_back(i);
        worker = std::this_thread::get_id();
      });
    writer.finish();
  }
  ASSERT_EQ(done.size(), 20u);
  for (int i = 0; i < 20; ++i) EXPECT_EQ(done[static_cast<std::size_t>(i)], i);
  EXPECT_NE(worker, std::this_thread::get_id());
}

TEST(FrameWriter, AFailureStopsTheJobsAfterItAndReachesTheCaller) {
  app::FrameWriter writer(4);
  std::vector<int> done;
  writer.submit([&] { done.push_back(0); });
  writer.submit([&] { throw std::runtime_error("disk full"); });
  writer.submit([&] { done.push_back(2); });
  try {
    writer.finish();
    FAIL() << "finish() must rethrow the job's failure";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "disk full");
  }
  EXPECT_EQ(done, std::vector<int>{0});
  EXPECT_THROW(writer.submit([&] { done.push_back(3); }), std::runtime_error);
  writer.settle();
  EXPECT_EQ(done, std::vector<int>{0});
}

}  // namespace
}  // namespace tallow
