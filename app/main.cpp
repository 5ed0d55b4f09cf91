// `tallow`: a thin dispatcher; every subcommand lives in app/*_command.cpp.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>

#include "app/capture_command.h"
#include "app/input_error.h"
#include "app/params.h"
#include "app/view_command.h"
#include "gpu/gl_context.h"
#include "gpu/shader_library.h"

namespace {

void addSceneOptions(CLI::App& cmd, tallow::app::SceneOptions& o) {
  cmd.add_option("--preset", o.preset, "preset name in presets/ or a path to a JSON file");
  cmd.add_option("--set", o.sets, "override a parameter: key=value (repeatable; see `tallow params`)");
  cmd.add_option("--size", o.size, "image size WIDTHxHEIGHT");
  cmd.add_option("--shader-dir", o.shaderDir, "read shaders from this folder instead of the embedded copy");
  cmd.add_flag("--explain", o.explain, "print the frame plan: which passes run and why");
}

int listParams() {
  const auto materials = tallow::sss::MaterialTable::load(tallow::app::dataDir() / "materials.csv");
  const tallow::app::Registry registry = tallow::app::parameterRegistry(materials);
  for (const auto& p : registry.params()) {
    std::string range;
    if (p.type == "int" || p.type == "float" || p.type == "vec3")
      range = "[" + tallow::app::formatNumber(p.min) + ", " + tallow::app::formatNumber(p.max) + "]";
    else if (p.type == "enum")
      range = std::to_string(p.choices.size()) + " choices";
    std::printf("%-24s %-6s %-22s %-10s %s\n", p.key.c_str(), p.type.c_str(), range.c_str(),
                p.defaultValue ? p.defaultValue->dump().c_str() : "(preset)", p.help.c_str());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Tallow: interactive directional subsurface scattering"};
  app.require_subcommand(0, 1);

  tallow::app::ViewOptions view;
  auto* viewCmd = app.add_subcommand("view", "open the preset in a window (the default command)");
  addSceneOptions(*viewCmd, view.scene);
  viewCmd->add_option("--frames", view.frames, "close after this many frames (0: when the window closes)");

  tallow::app::CaptureOptions capture;
  auto* captureCmd = app.add_subcommand("capture", "render frames headless into PNG, EXR and stats.json");
  addSceneOptions(*captureCmd, capture.scene);
  captureCmd->add_option("--out", capture.outDir, "output folder")->required();
  captureCmd->add_option("--frames", capture.frames, "number of frames");
  captureCmd->add_option("--time", capture.timeS, "animation time of the first frame [s]");
  captureCmd->add_option("--fps", capture.fps, "frames per second of the sequence");
  captureCmd->add_option("--gl", capture.gl, "OpenGL context: osmesa (default) or egl")
      ->check(CLI::IsMember({"osmesa", "egl"}));
  captureCmd->add_flag("--exr-float", capture.exrFloat, "write 32-bit float EXR channels instead of half");

  auto* paramsCmd = app.add_subcommand("params", "list every parameter: key, type, range, default, help");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "tallow: %s\n", e.what());
    return 2;
  }

  try {
    if (*captureCmd) return tallow::app::runCapture(capture);
    if (*paramsCmd) return listParams();
    return tallow::app::runView(view);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tallow: %s\n", e.what());
    return 1;
  }
}
