#pragma once
// The device bench's report (scripts/device_bench.sh, docs/device-bench.md): reads the folder of
// one bench run — meta.tsv (the machine), rows.tsv (each row's status, time and command) and each
// row's stats.json (`tallow capture`) or maps.json (`tallow probe maps`) — and derives the figures
// of issue 18: frames per second of the animated and the converged candle, the gather's arithmetic
// rate against the GPU's FP32 peak, dual-contouring cells per second, and cached against no-cache
// by screen occupancy. Rows that failed or were skipped are listed, never dropped.
#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>
#include <string>

#include "app/bench_report/gather_flops.h"

namespace tallow::bench_report {

/// The FP32 peak of an NVIDIA GPU in TFLOP/s from its nvidia-smi name and maximum SM clock:
/// SMs × 128 FP32 lanes × 2 (an FMA counts two) × clock, for the Hopper parts whose SM counts are
/// known here; nullopt for any other name.
std::optional<double> hopperFp32PeakTflops(const std::string& nvidiaSmiName, double maxSmClockMhz);

/// Reads `runs` (the bench's runs/ folder) and returns results.json's content. `flops` is the
/// counted FLOPs per gather sample (gather_flops.h). Throws std::runtime_error (one line naming the
/// file) when meta.tsv or rows.tsv is missing or malformed; a row's unreadable output becomes that
/// row's "error", not an exception.
nlohmann::json buildReport(const std::filesystem::path& runs, const flops::GatherFlops& flops,
                           const nlohmann::json& bundle);

/// results.md from buildReport's JSON.
std::string renderMarkdown(const nlohmann::json& report);

}  // namespace tallow::bench_report
