// `tallow_bench_report`: the device bench's report (scripts/device_bench.sh calls it after the
// rows). Reads the bench's runs/ folder, counts the gather's FLOPs per sample from the shared
// shader lines, and writes results.json and results.md into --out, each whole or not at all.
//
//   tallow_bench_report --runs DIR --materials materials.csv --out DIR [--bundle bundle.json]
//   tallow_bench_report --flops --materials materials.csv     # the count alone, as JSON
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>

#include "app/bench_report/bench_report.h"
#include "app/bench_report/gather_flops.h"
#include "gpu/atomic_file.h"
#include "sss/bssrdf/material.h"

namespace {

/// The material of the gather rows' scene (presets/bunny.json): the count is made for its bands.
constexpr const char* kGatherMaterial = "Marble";
/// Samples per band: the count depends on branches, not on the sample, so a few suffice; more
/// would only confirm it.
constexpr int kSamplesPerBand = 64;

int usage(const char* why) {
  std::fprintf(stderr, "tallow_bench_report: %s\n", why);
  std::fprintf(stderr, "usage: tallow_bench_report --runs DIR --materials CSV --out DIR [--bundle FILE] | --flops --materials CSV\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::filesystem::path runs, materials, out, bundle;
  bool flopsOnly = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&](std::filesystem::path& into) {
      if (i + 1 >= argc) return false;
      into = argv[++i];
      return true;
    };
    if (arg == "--flops") flopsOnly = true;
    else if (arg == "--runs") { if (!value(runs)) return usage("--runs needs a folder"); }
    else if (arg == "--materials") { if (!value(materials)) return usage("--materials needs a file"); }
    else if (arg == "--out") { if (!value(out)) return usage("--out needs a folder"); }
    else if (arg == "--bundle") { if (!value(bundle)) return usage("--bundle needs a file"); }
    else return usage(("unknown argument \"" + arg + "\"").c_str());
  }
  if (materials.empty()) return usage("--materials CSV is required");
  if (!flopsOnly && (runs.empty() || out.empty())) return usage("--runs DIR and --out DIR are required");
  try {
    const auto table = tallow::sss::MaterialTable::load(materials);
    const auto material = table.find(kGatherMaterial);
    if (!material) throw std::runtime_error(materials.string() + ": no material \"" + kGatherMaterial + "\"");
    const tallow::flops::GatherFlops flops =
        tallow::flops::countGatherFlops(*material, tallow::sss::BssrdfModel::Directional, kSamplesPerBand);
    if (flopsOnly) {
      const auto loop = [](const tallow::flops::LoopFlops& l) {
        return nlohmann::json{{"samples", l.samples},
                              {"flops_mean", l.flopsMean},
                              {"flops_per_shared_sample", l.flopsPerSharedSample},
                              {"flops_shared_min", l.flopsSharedMin},
                              {"flops_shared_max", l.flopsSharedMax},
                              {"flops_per_texel", l.flopsPerTexel}};
      };
      std::printf("%s\n", nlohmann::json({{"material", kGatherMaterial},
                                          {"model", "directional"},
                                          {"directional_light", loop(flops.directional)},
                                          {"point_light", loop(flops.point)},
                                          {"max_difference_to_float", flops.maxValueDifference}})
                              .dump(2)
                              .c_str());
      return 0;
    }
    nlohmann::json bundleInfo = nullptr;
    if (!bundle.empty()) {
      std::ifstream in(bundle);
      if (!in) throw std::runtime_error(bundle.string() + ": cannot be read");
      bundleInfo = nlohmann::json::parse(in);
    }
    nlohmann::json report = tallow::bench_report::buildReport(runs, flops, bundleInfo);
    report["gather_flops"]["material"] = kGatherMaterial;
    std::filesystem::create_directories(out);
    tallow::gpu::writeTextFileAtomically(out / "results.json", report.dump(2) + "\n");
    tallow::gpu::writeTextFileAtomically(out / "results.md", tallow::bench_report::renderMarkdown(report));
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tallow_bench_report: %s\n", e.what());
    return 1;
  }
}
