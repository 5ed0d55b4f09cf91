#include "app/commands/probe_command.h"

#include <cstdio>
#include <fstream>
#include <sstream>

#include "app/commands/bssrdf_csv.h"
#include "app/commands/option_checks.h"
#include "app/config/input_error.h"
#include "app/config/setup.h"
#include "gpu/atomic_file.h"
#include "gpu/gl_context.h"
#include "sss/bssrdf/bssrdf.h"
#include "sss/bssrdf/bssrdf_gpu.h"

namespace tallow::app {

int runProbeBssrdf(const ProbeBssrdfOptions& options) {
  sss::BssrdfModel model;
  try {
    model = sss::parseBssrdfModel(options.model);
  } catch (const std::invalid_argument& e) {
    throw InputError(std::string("--model: ") + e.what());
  }
  const std::string precision = options.precision.empty() ? (options.gpu ? "float" : "double") : options.precision;
  if (precision != "float" && precision != "double")
    throw InputError("--precision: expected float or double, got \"" + precision + "\"");
  if (options.gpu && precision == "double")
    throw InputError("--gpu evaluates in float (GLSL 4.5 has no double-precision exp or pow)");
  checkOutputFile("--out", options.out);
  const std::vector<sss::BssrdfConfig> configs = parseInputFile(
      options.in, [&](const std::string& text) { return parseBssrdfConfigs(text, options.in); }, gpu::kMaxTableFileBytes,
      "a CSV table");

  std::vector<sss::BssrdfValue> values;
  if (options.gpu) {
    gpu::ContextOptions contextOptions;
    contextOptions.backend = gpu::parseGlBackend(options.gl);
    auto context = gpu::GlContext::create(contextOptions);
    values = sss::evaluateBssrdfGpu(gpu::ShaderLibrary(), model, configs, options.reciprocal);
  } else {
    values.reserve(configs.size());
    for (const auto& c : configs)
      values.push_back(precision == "float" ? sss::evaluateBssrdf<float>(model, c, options.reciprocal)
                                                    : sss::evaluateBssrdf<double>(model, c, options.reciprocal));
  }
  gpu::writeTextFileAtomically(options.out, formatBssrdfValues(configs, values));
  std::printf("tallow: %zu configuration(s), %s model, %s%s -> %s\n", configs.size(),
              std::string(sss::bssrdfModelName(model)).c_str(), options.gpu ? "GLSL " : "", precision.c_str(),
              options.out.c_str());
  return 0;
}

}  // namespace tallow::app
