// `tallow`: a thin dispatcher; every subcommand lives in app/*_command.cpp.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <new>
#include <string_view>
#include <vector>

#include "app/command_line_errors.h"
#include "app/commands/bench_command.h"
#include "app/commands/capture_command.h"
#include "app/commands/compare_command.h"
#include "app/commands/cost_command.h"
#include "app/commands/extraction_bench_command.h"
#include "app/commands/placement_probe_command.h"
#include "app/commands/field_command.h"
#include "app/commands/maps_bench_command.h"
#include "app/commands/mesh_command.h"
#include "app/commands/probe_command.h"
#include "app/commands/provenance.h"
#include "app/commands/profile_command.h"
#include "app/commands/reference_command.h"
#include "app/config/input_error.h"
#include "app/config/params.h"
#include "app/config/setup.h"
#include "app/view/view_command.h"
#include "gpu/gl_context.h"
#include "gpu/shader_library.h"

namespace {

/// `--preset ""` is refused rather than read as "no --preset" (the default preset).
CLI::Validator presetNamed() {
  return tallow::app::nonEmpty("give a name from presets/ or a JSON file, or leave --preset out for the default");
}

void addSceneOptions(CLI::App& cmd, tallow::app::SceneOptions& o) {
  cmd.add_option("--preset", o.preset, "preset name in presets/ or a path to a JSON file")->check(presetNamed());
  cmd.add_option("--set", o.sets, "override a parameter: key=value (repeatable; see `tallow params`)");
  cmd.add_option("--size", o.size, "image size WIDTHxHEIGHT");
  cmd.add_option("--shader-dir", o.shaderDir, "read shaders from this folder instead of the embedded copy");
  cmd.add_flag("--explain", o.explain, "print the frame plan: which passes run and why");
}

/// `tallow params`: every parameter with its default; with --preset (or --set), the value that
/// preset gives it instead, in a column headed by the preset's name.
int listParams(const tallow::app::SceneOptions& scene, bool forPreset) {
  const auto materials = tallow::sss::MaterialTable::load(tallow::app::dataDir() / "materials.csv");
  const tallow::app::Registry registry = tallow::app::parameterRegistry(materials);
  nlohmann::json values;
  if (forPreset) {
    const tallow::app::LoadedScene loaded = tallow::app::loadScene(scene);
    values = registry.snapshot(loaded.config);
    std::printf("%-24s %-6s %-22s %-10s %s\n", "key", "type", "range", ("[" + loaded.presetName + "]").c_str(), "help");
  }
  for (const auto& p : registry.params()) {
    std::string range;
    if (p.type == "int" || p.type == "float" || p.type == "vec3")
      range = "[" + tallow::app::formatNumber(p.min) + ", " + tallow::app::formatNumber(p.max) + "]";
    else if (p.type == "enum")
      range = std::to_string(p.choices.size()) + " choices";
    const std::string value = forPreset && values.contains(p.key) ? values[p.key].dump()
                              : p.defaultValue                    ? p.defaultValue->dump()
                                                                  : "(preset)";
    std::printf("%-24s %-6s %-22s %-10s %s\n", p.key.c_str(), p.type.c_str(), range.c_str(), value.c_str(), p.help.c_str());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  tallow::app::recordCommandLine(argc, argv);  // stats.json's provenance
  CLI::App app{"Tallow: interactive directional subsurface scattering"};
  app.require_subcommand(0, 1);

  tallow::app::ViewOptions view;
  auto* viewCmd = app.add_subcommand("view", "open the preset in a window (the default command)");
  addSceneOptions(*viewCmd, view.scene);
  viewCmd->add_option("--frames", view.frames, "close after this many frames (0: when the window closes)");
  viewCmd->add_option("--screenshot", view.screenshots, "after the last of --frames (needed) save FILE.png (the window, panel included) or FILE.exr (the radiance), its folder created; repeatable");
  viewCmd->add_option("--save-preset", view.savePreset, "after the last of --frames (needed) save a preset that `capture --preset FILE` renders as shown");
  viewCmd->add_option("--script", view.script, "timed commands, e.g. `frame 5 set sss.maps=8` (docs/view.md)");
  viewCmd->add_option("--stats", view.stats, "write stats.json of the run (per frame: timings, changed parameters, maps)");
  viewCmd->add_option("--reference", view.reference, "REF.exr for the difference debug view (e.g. from `tallow reference`)");
  viewCmd->add_option("--debug-view", view.debugView, "start in a debug view: final, gbuffer-position[:L[:F]], gbuffer-normal[:L[:F]], map[:K], coverage, vpl, wireframe, difference");
  viewCmd->add_option("--fps", view.fps, "advance the animation by 1/fps per frame instead of by wall time");
  viewCmd->add_option("--max-step", view.maxStepS, "by wall time, advance the animation at most this many seconds per frame, so a slow machine plays slower instead of skipping (default 1/30; 0: no cap)");
  viewCmd->add_option("--time", view.timeS, "animation time of the first frame [s] (default: the preset's start_s)");
  viewCmd->add_flag("--paused", view.paused, "start with the animation paused");
  viewCmd->add_flag("--no-panel", view.hidePanel, "hide the ImGui panel");
  viewCmd->add_option("--vsync", view.vsync, "wait for the display's refresh at each frame (true, the default, or false: as fast as the GPU renders, for timing)");

  tallow::app::CaptureOptions capture;
  auto* captureCmd = app.add_subcommand("capture", "render frames headless into PNG, EXR and stats.json");
  addSceneOptions(*captureCmd, capture.scene);
  captureCmd->add_option("--out", capture.outDir, "output folder")->required();
  captureCmd->add_option("--frames", capture.frames, "number of frames");
  captureCmd->add_option("--time", capture.timeS, "animation time of the first frame [s]");
  captureCmd->add_option("--fps", capture.fps, "frames per second of the sequence");
  captureCmd->add_option("--accumulate", capture.accumulate,
                         "renders per frame at its time, the last written: progressive methods accumulate (default 1)");
  captureCmd->add_option("--gl", capture.gl, "OpenGL context: osmesa (default) or egl")
      ->check(CLI::IsMember({"osmesa", "egl"}));
  captureCmd->add_flag("--exr-float", capture.exrFloat, "write 32-bit float EXR channels instead of half");
  captureCmd->add_option("--script", capture.script, "timed parameter changes, e.g. `frame 5 set sss.maps=8` (docs/view.md)");
  captureCmd->add_option("--video", capture.video, "also encode the frames into a video with ffmpeg (.mp4, .mov, .mkv, .webm)");
  captureCmd->add_option("--reference", capture.reference,
                         "REF.exr from `tallow reference` (REF_stderr.exr beside it): each frame's error against it in stats.json");

  tallow::app::ReferenceOptions reference;
  auto* referenceCmd = app.add_subcommand("reference", "CPU ground truth (Embree, TBB): the capture image by Monte Carlo integration of the BSSRDF");
  addSceneOptions(*referenceCmd, reference.scene);
  referenceCmd->add_option("--out", reference.out, "REF.exr (REF_stderr.exr beside it)")->required();
  referenceCmd->add_option("--time", reference.timeS, "animation time [s]");
  referenceCmd->add_option("--spp", reference.spp, "passes (each with fresh surface points)");
  referenceCmd->add_option("--rel-error", reference.relError, "stop at this relative standard error (docs/reference.md)");
  referenceCmd->add_option("--points", reference.points, "surface points per translucent object and pass (0: automatic)");
  referenceCmd->add_option("--seed", reference.seed, "random seed");
  referenceCmd->add_option("--threads", reference.threads, "worker threads (0: all cores)");
  referenceCmd->add_option("--pixel-filter", reference.pixelFilter,
                           "box: each pass through its own point of the pixel (the mean over its square, as a "
                           "still with render.aa), or centre: every pass through the pixel centre (default box)")
      ->check(CLI::IsMember({"box", "centre"}));
  referenceCmd->add_flag(tallow::app::emergentFlag(), reference.emergent, "light leaving the translucent objects onto the receivers; =N: emitter points per object and pass (docs/reference.md)");
  referenceCmd->add_flag("--cpu-mesher", reference.cpuMesher, "mesh field objects with OpenVDB volumeToMesh instead of taking the GPU's triangles (docs/reference.md)");
  referenceCmd->add_option("--gl", reference.gl, "OpenGL context that contours field objects: osmesa (default) or egl")->check(CLI::IsMember({"osmesa", "egl"}));

  tallow::app::BenchOptions bench;
  auto* benchCmd = app.add_subcommand("bench", "speed against error: every method and swept setting timed and compared with the CPU reference");
  addSceneOptions(*benchCmd, bench.scene);
  benchCmd->add_option("--out", bench.outDir, "output folder")->required();
  benchCmd->add_option("--time", bench.timeS, "animation time [s]");
  benchCmd->add_option("--methods", bench.methods, "values of `method`, e.g. radiosity-maps,no-cache,image-space,albedo (default: all)")->delimiter(',');
  benchCmd->add_option("--sweep", bench.sweeps, "key=v1,v2,...: one row per value (repeatable: the Cartesian product)");
  benchCmd->add_option("--frames", bench.frames, "timed frames after the restart (at least 5; at least sss.frames + 2)");
  benchCmd->add_option("--reference", bench.reference, "REF.exr from `tallow reference` (REF_stderr.exr beside it)");
  benchCmd->add_option("--ref-rel-error", bench.refRelError, "compute the reference to this relative standard error");
  benchCmd->add_option("--ref-spp", bench.refSpp, "compute the reference with this many passes");
  benchCmd->add_option("--ref-points", bench.refPoints, "reference surface points per translucent object and pass (0: automatic)");
  benchCmd->add_flag("--equal-time", bench.equalTime, "also run the reference for as long as each row's first frame");
  benchCmd->add_flag("--receivers", bench.receivers, "also compare the receivers' VPL term with the reference's emergent light (docs/vpl.md)");
  benchCmd->add_option("--gl", bench.gl, "OpenGL context: osmesa (default) or egl")->check(CLI::IsMember({"osmesa", "egl"}));

  tallow::app::CompareOptions compare;
  auto* compareCmd = app.add_subcommand("compare", "two EXR renders side by side with their difference in false colour, as one PNG, and/or their error as JSON");
  compareCmd->add_option("a", compare.a, "A.exr")->required();
  compareCmd->add_option("b", compare.b, "B.exr (the difference is relative to its RMS radiance)")->required();
  compareCmd->add_option("--out", compare.out, "FIG.png");
  compareCmd->add_option("--json", compare.json, "ERR.json: A's error against B over the mask (relative RMSE, mean ratio overall and per half, fireflies of both)");
  compareCmd->add_option("--caption", compare.captions, "caption of A, then of B (default: each file's folder and name)");
  compareCmd->add_option("--max-rel-rmse", compare.maxRelRmse, "fail (exit 3, one line) when A's relative RMSE against B is above this, e.g. 0.02: a golden-image test");
  compareCmd->add_option("--max-new-fireflies", compare.maxNewFireflies, "fail (exit 3, one line) when A has more fireflies than this at pixels where B has none");
  compareCmd->add_option("--title", compare.title, "title above the pictures");
  compareCmd->add_option("--mask", compare.mask, "EXR whose alpha >= 0.5 marks the pixels compared (e.g. REF_stderr.exr)");
  compareCmd->add_option("--exposure-ev", compare.exposureEv, "exposure before the tone map [stops]");
  compareCmd->add_option("--scale", compare.scale, "top of the colour scale as a fraction, e.g. 0.2 (default: from the difference)");
  compareCmd->add_flag("--ignore-non-finite", compare.ignoreNonFinite,
                       "leave out the pixels where A or B is NaN or infinite (counted) instead of failing");

  auto* paramsCmd = app.add_subcommand("params", "list every parameter: key, type, range, default (or a preset's value), help");
  tallow::app::SceneOptions paramsScene;
  paramsCmd->add_option("--preset", paramsScene.preset, "show this preset's values instead of the defaults")->check(presetNamed());
  paramsCmd->add_option("--set", paramsScene.sets, "with the preset: override a parameter, key=value (repeatable)");

  auto* probeCmd = app.add_subcommand("probe", "evaluate parts of the method outside a scene (BSSRDF, extraction)");
  probeCmd->require_subcommand(1);
  tallow::app::ProbeBssrdfOptions probeBssrdf;
  auto* probeBssrdfCmd = probeCmd->add_subcommand("bssrdf", "evaluate S_d for each configuration of a CSV file");
  probeBssrdfCmd->add_option("--model", probeBssrdf.model, "standard | directional | pbd")->required();
  probeBssrdfCmd->add_option("--precision", probeBssrdf.precision, "float | double (default: double, float with --gpu)");
  probeBssrdfCmd->add_flag("--gpu", probeBssrdf.gpu, "evaluate the GLSL in a compute shader");
  probeBssrdfCmd->add_option("--gl", probeBssrdf.gl, "OpenGL context for --gpu: osmesa (default) or egl")
      ->check(CLI::IsMember({"osmesa", "egl"}));
  probeBssrdfCmd->add_flag("--reciprocal", probeBssrdf.reciprocal,
                           "average with the swapped evaluation (directional dipole paper, section 6.3)");
  probeBssrdfCmd->add_option("--in", probeBssrdf.in, "CONFIGS.csv")->required();
  probeBssrdfCmd->add_option("--out", probeBssrdf.out, "VALUES.csv")->required();

  tallow::app::ProbeProfileOptions profile;
  auto* profileCmd = probeCmd->add_subcommand("profile", "R_d of a planar medium along x and as a 2D map, CSV + PNG");
  profileCmd->add_option("--model", profile.model, "standard | directional | pbd | mc (volumetric Monte Carlo)")->required();
  profileCmd->add_option("--material", profile.material, "material name from materials.csv");
  profileCmd->add_option("--band", profile.band, "colour band of --material: 0 red, 1 green, 2 blue");
  profileCmd->add_option("--sigma-a", profile.sigmaA, "absorption coefficient [1/mm]");
  profileCmd->add_option("--sigma-s", profile.sigmaS, "scattering coefficient [1/mm]");
  profileCmd->add_option("--g", profile.g, "Henyey-Greenstein mean cosine");
  profileCmd->add_option("--eta", profile.eta, "relative index of refraction");
  profileCmd->add_option("--theta", profile.thetaDeg, "angle of incidence [degrees]");
  profileCmd->add_option("--extent", profile.extentMm, "side of the plotted square [mm]");
  profileCmd->add_option("--bins", profile.bins, "samples along x and per side of the map");
  profileCmd->add_option("--photons", profile.photons, "photon packets for --model mc");
  profileCmd->add_option("--seed", profile.seed, "random seed for --model mc");
  profileCmd->add_flag("!--no-plots", profile.plots, "write the CSV files only");
  profileCmd->add_option("--out", profile.out, "output folder")->required();

  tallow::app::ProbeCostOptions cost;
  auto* costCmd = probeCmd->add_subcommand("cost", "evaluations per second of each model (CPU float/double, GLSL)");
  costCmd->add_option("--count", cost.count, "configurations per model");
  costCmd->add_option("--repeats", cost.repeats, "timed repeats; the median is reported");
  costCmd->add_flag("!--no-gpu", cost.gpu, "skip the GLSL compute path");
  costCmd->add_option("--gl", cost.gl, "OpenGL context: osmesa (default) or egl")->check(CLI::IsMember({"osmesa", "egl"}));
  costCmd->add_option("--out", cost.out, "JSON file")->required();

  tallow::app::ProbeExtractionOptions extraction;
  auto* extractionCmd = probeCmd->add_subcommand("extraction", "isosurface extraction benchmark: GPU dual contouring vs OpenVDB");
  extractionCmd->add_option("--fields", extraction.fields, "fields: blob,candle")->delimiter(',');
  extractionCmd->add_option("--res", extraction.resolutions, "samples per axis, each in [16, 256]")->delimiter(',');
  extractionCmd->add_option("--repeats", extraction.repeats, "timed repeats after one warm-up; the median is reported");
  extractionCmd->add_option("--gl", extraction.gl, "OpenGL context: osmesa (default) or egl")->check(CLI::IsMember({"osmesa", "egl"}));
  extractionCmd->add_option("--out", extraction.out, "JSON file")->required();

  tallow::app::ProbePlacementOptions placement;
  auto* placementCmd = probeCmd->add_subcommand(
      "placement", "dual contouring's vertex placements (mass, qef) against the exact surface: Hausdorff distances");
  placementCmd->add_option("--shapes", placement.shapes, "shapes: cube,candle,sphere,blob")->delimiter(',');
  placementCmd->add_option("--res", placement.resolutions, "samples per axis, each in [16, 256]")->delimiter(',');
  placementCmd->add_option("--repeats", placement.repeats, "timed extractions after one warm-up; the median is reported");
  placementCmd->add_option("--gl", placement.gl, "OpenGL context: osmesa (default) or egl")->check(CLI::IsMember({"osmesa", "egl"}));
  placementCmd->add_option("--out", placement.out, "JSON file")->required();

  tallow::app::ProbeMapsOptions mapsBench;
  auto* mapsBenchCmd = probeCmd->add_subcommand("maps", "cost of the scattered radiosity maps against K and N");
  mapsBenchCmd->add_option("--preset", mapsBench.scene.preset, "preset name in presets/ or a path to a JSON file")
      ->check(presetNamed());
  mapsBenchCmd->add_option("--set", mapsBench.scene.sets, "override a parameter: key=value (repeatable; see `tallow params`)");
  mapsBenchCmd->add_option("--size", mapsBench.scene.size, "image size WIDTHxHEIGHT");
  mapsBenchCmd->add_option("--shader-dir", mapsBench.scene.shaderDir, "read shaders from this folder instead of the embedded copy");
  mapsBenchCmd->add_option("--k", mapsBench.maps, "numbers of maps K (sss.maps), e.g. 4,8,16,32")->delimiter(',');
  mapsBenchCmd->add_option("--n", mapsBench.samples, "samples per texel N (sss.samples), e.g. 1,4,16")->delimiter(',');
  mapsBenchCmd->add_option("--map-size", mapsBench.mapSize, "sss.map_size (default: the preset's)");
  mapsBenchCmd->add_option("--repeats", mapsBench.repeats, "timed frames after one warm-up; the median is reported");
  mapsBenchCmd->add_option("--gather", mapsBench.gather, "sss.gather (default: the preset's)");
  mapsBenchCmd->add_option("--gl", mapsBench.gl, "OpenGL context: osmesa (default) or egl")->check(CLI::IsMember({"osmesa", "egl"}));
  mapsBenchCmd->add_option("--out", mapsBench.out, "JSON file")->required();

  tallow::app::MeshOptions mesh;
  auto* meshCmd = app.add_subcommand("mesh", "write the triangles of the preset's field objects at time T as a PLY or OBJ (world units), or with --frames N the animation as a numbered sequence");
  meshCmd->add_option("--preset", mesh.scene.preset, "preset name in presets/ or a path to a JSON file")->check(presetNamed());
  meshCmd->add_option("--set", mesh.scene.sets, "override a parameter: key=value (repeatable; see `tallow params`)");
  meshCmd->add_option("--time", mesh.timeS, "animation time [s]");
  meshCmd->add_option("--res", mesh.res, "lattice samples per axis (default: field.res)");
  meshCmd->add_flag("--cpu", mesh.cpu, "mesh with OpenVDB volumeToMesh on the same lattice instead of the GPU");
  meshCmd->add_option("--gl", mesh.gl, "OpenGL context: osmesa (default) or egl")->check(CLI::IsMember({"osmesa", "egl"}));
  meshCmd->add_option("--out", mesh.out, "MESH.ply or MESH.obj; with --frames, the sequence MESH_0000.ply, … (.obj)")->required();
  meshCmd->add_option("--frames", mesh.frames, "write N meshes at --time + i / --fps, numbered (a mesh sequence for DCC tools)");
  meshCmd->add_option("--fps", mesh.fps, "the sequence's frames per second (default 30)");

  tallow::app::FieldOptions field;
  auto* fieldCmd = app.add_subcommand("field", "evaluate the preset's field (value < 0 inside, gradient) at the points of a CSV");
  fieldCmd->add_option("--preset", field.scene.preset, "preset name in presets/ or a path to a JSON file")->check(presetNamed());
  fieldCmd->add_option("--set", field.scene.sets, "override a parameter: key=value (repeatable; see `tallow params`)");
  fieldCmd->add_option("--time", field.timeS, "animation time [s]");
  fieldCmd->add_option("--in", field.in, "POINTS.csv (header x,y,z; metres)")->required();
  fieldCmd->add_option("--out", field.out, "VALUES.csv")->required();

  // `view` is the default command: `tallow --preset blob` is `tallow view --preset blob`, as the
  // README's synopsis writes it (only --help stays the program's own).
  std::vector<char*> args(argv, argv + argc);
  static char viewWord[] = "view";
  if (argc > 1 && argv[1][0] == '-' && std::string_view(argv[1]) != "-h" && std::string_view(argv[1]) != "--help")
    args.insert(args.begin() + 1, viewWord);
  try {
    app.parse(static_cast<int>(args.size()), args.data());
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "tallow: %s\n", tallow::app::describeParseError(app, e, static_cast<int>(args.size()), args.data()).c_str());
    return 2;
  }

  try {
    if (*captureCmd) return tallow::app::runCapture(capture);
    if (*referenceCmd) return tallow::app::runReference(reference);
    if (*benchCmd) return tallow::app::runBench(bench);
    if (*compareCmd) return tallow::app::runCompare(compare);
    if (*paramsCmd) return listParams(paramsScene, !paramsScene.preset.empty() || !paramsScene.sets.empty());
    if (*probeBssrdfCmd) return tallow::app::runProbeBssrdf(probeBssrdf);
    if (*profileCmd) return tallow::app::runProbeProfile(profile);
    if (*costCmd) return tallow::app::runProbeCost(cost);
    if (*extractionCmd) return tallow::app::runProbeExtraction(extraction);
    if (*placementCmd) return tallow::app::runProbePlacement(placement);
    if (*mapsBenchCmd) return tallow::app::runProbeMaps(mapsBench);
    if (*meshCmd) return tallow::app::runMesh(mesh);
    if (*fieldCmd) return tallow::app::runField(field);
    return tallow::app::runView(view);
  } catch (const std::bad_alloc&) {
    // The readers name the file they were reading; this is what is left: a CPU allocation sized by
    // the command line (images of --size, the reference's buffers) that did not fit.
    std::fprintf(stderr, "tallow: %s: out of memory: an allocation sized by the command's settings failed (lower "
                         "--size or the sizes in --set)\n", tallow::app::selectedCommandName(app).c_str());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tallow: %s\n", e.what());
    return 1;
  }
}
