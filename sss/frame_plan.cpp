#include "sss/frame_plan.h"

#include <cstdio>
#include <stdexcept>

#include "sss/maps/maps_method.h"
#include "sss/peers/burley.h"
#include "sss/peers/image_space_method.h"
#include "sss/peers/sslpv_method.h"

namespace tallow::sss {

std::vector<std::unique_ptr<TranslucencyMethod>> makeTranslucencyMethods() {
  std::vector<std::unique_ptr<TranslucencyMethod>> m;
  const auto lightGBuffers = std::make_shared<LightGBufferPass>();  // step 1 of both
  m.push_back(std::make_unique<RadiosityMapsMethod>(lightGBuffers));
  m.push_back(std::make_unique<NoCacheMethod>(lightGBuffers));
  m.push_back(std::make_unique<SslpvMethod>());
  m.push_back(std::make_unique<ImageSpaceMethod>());
  m.push_back(std::make_unique<BurleyMethod>());
  m.push_back(std::make_unique<AlbedoMethod>());
  return m;
}

FramePlan::FramePlan() : methods_(makeTranslucencyMethods()), camera_(*methods_.front()) {}

TranslucencyMethod& FramePlan::method(const FrameState& state) {
  for (const auto& m : methods_)
    if (m->id() == state.settings.sss.method) return *m;
  throw std::logic_error("no translucency method for method " +
                         std::to_string(static_cast<int>(state.settings.sss.method)));
}

std::vector<Pass*> FramePlan::passes(const FrameState& state) {
  std::vector<Pass*> out;
  for (FramePass* p : std::initializer_list<FramePass*>{&fieldSample_, &fieldExtract_, &directionalShadow_, &pointShadow_})
    if (p->needed(state)) out.push_back(p);
  TranslucencyMethod& m = method(state);
  for (Pass* p : m.passes(state)) out.push_back(p);
  camera_.setMethod(m);
  out.push_back(&camera_);
  for (Pass* p : m.afterCamera(state)) out.push_back(p);
  if (flame_.needed(state)) out.push_back(&flame_);
  if (still_.needed(state)) out.push_back(&still_);  // it averages the finished picture
  if (bloom_.needed(state)) out.push_back(&bloom_);  // the glare of the picture shown
  if (localExposure_.needed(state)) out.push_back(&localExposure_);  // last: the eye's adaptation
  return out;
}

std::vector<PlannedPass> FramePlan::describe(const FrameState& state) {
  std::vector<PlannedPass> out;
  for (Pass* p : passes(state)) out.push_back({p->name(), p->reason(state), p->io(state)});
  return out;
}

std::string formatPlan(const std::vector<PlannedPass>& plan, const std::string& prefix) {
  const auto list = [](const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
    return out.empty() ? std::string("-") : out;
  };
  std::string out;
  for (const PlannedPass& p : plan) {
    char head[64];
    std::snprintf(head, sizeof head, "pass %-20s ", p.name.c_str());
    out += prefix + head + p.reason + "\n";
    out += prefix + "     reads " + list(p.io.reads);
    if (!p.io.paces.empty()) out += "; paced by " + list(p.io.paces);
    out += "; writes " + list(p.io.writes) + "\n";
  }
  return out;
}

}  // namespace tallow::sss
