#include "wavelet_commands.h"

#include <CLI/CLI.hpp>

#include <chrono>
#include <filesystem>
#include <iostream>

#include "dwt/error.h"
#include "dwt/kernel.h"
#include "dwt/params.h"
#include "imageio/read.h"
#include "imageio/write.h"
#include "quiet_stderr.h"
#include "wavelet_apps/band_spec.h"
#include "wavelet_apps/control_net.h"
#include "wavelet_apps/engine.h"
#include "wavelet_apps/image_apps.h"
#include "wavelet_apps/picture.h"

namespace dwtool {

namespace wa = wavelet_apps;

namespace {

void add_engine_options(CLI::App& c, AppOptions& o) {
  c.add_option("--levels", o.levels, "Decomposition levels (default 5 for images, 3 for control nets)");
  c.add_option("--kernel", o.kernel, "Float wavelet: 97|53f|haar")->capture_default_str();
  c.add_option("--boundary", o.boundary, "Boundary extension: sym|per|zero")->capture_default_str();
  c.add_option("--backend", o.backend, "cpu|gpu (gpu: forward, band pass and inverse stay on the GPU)")
      ->capture_default_str();
  c.add_option("--threads", o.threads, "CPU threads, 0 = all hardware threads")->capture_default_str();
  c.add_option("--gl", o.gl, "GL platform for --backend gpu: auto|egl-device|egl-surfaceless|osmesa");
  c.add_flag("-q,--quiet", o.quiet, "Print nothing but errors");
}

std::string lower_extension(const std::string& path) {
  std::string e = std::filesystem::path(path).extension().string();
  for (char& ch : e) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return e;
}

dwt::DwtParams resolve_params(const AppOptions& o, int default_levels) {
  dwt::DwtParams p;
  p.kernel = dwt::parse_kernel(o.kernel);
  if (dwt::get_kernel(p.kernel).reversible)
    throw std::invalid_argument(
        "the wavelet applications scale coefficients, so they need a float kernel (97, 53f, haar)");
  p.boundary = dwt::parse_boundary(o.boundary);
  p.levels = o.levels < 0 ? default_levels : o.levels;
  return p;
}

std::unique_ptr<wa::WaveletEngine> make_engine(const AppOptions& o) {
  const wa::EngineKind kind = wa::parse_engine_kind(o.backend);
  if (o.threads < 0 || o.threads > 1024) throw std::invalid_argument("--threads must be 0..1024");
  const glc::Platform platform = kind == wa::EngineKind::Gpu
                                     ? (o.gl.empty() ? glc::platform_from_env() : glc::parse_platform(o.gl))
                                     : glc::Platform::Auto;
  return wa::make_engine(kind, o.threads, platform);
}

imageio::Image read_input(const std::string& path) {
  const cli::QuietStderr quiet_libraries;
  return imageio::read_image(path);
}

void check_levels(const std::string& path, const dwt::DwtParams& params, const imageio::Image& image) {
  try {
    dwt::validate(params, image.width, image.height);
  } catch (const dwt::DwtError& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
}

// Before the clock starts, so context creation is reported apart.
void announce(const AppOptions& o, wa::WaveletEngine& engine) {
  const std::string what = engine.prepare();
  if (!o.quiet) std::cerr << "dwtool: " << (o.backend == "gpu" ? "renderer: " : "backend: ") << what << '\n';
}

using Clock = std::chrono::steady_clock;
void report(const AppOptions& o, const char* what, Clock::time_point start) {
  if (o.quiet) return;
  std::cerr << "dwtool: " << what << " in " << std::chrono::duration<double, std::milli>(Clock::now() - start).count()
            << " ms (" << o.backend << ")\n";
}

void run_edit(const AppOptions& o) {
  const imageio::Image image = read_input(o.input);
  wa::EditSettings s;
  s.params = resolve_params(o, 5);
  s.space = wa::parse_colour_space(o.space.empty() ? "rgb" : o.space);
  check_levels(o.input, s.params, image);
  const auto names = wa::channel_names(image.channels, s.space);
  for (const std::string& b : o.bands) s.bands.push_back(wa::parse_scale_spec(b, names, s.params.levels));
  auto engine = make_engine(o);
  announce(o, *engine);
  const auto t0 = Clock::now();
  const imageio::Image out = wa::edit_image(image, s, *engine);
  report(o, "edit (forward, band operation, inverse)", t0);
  imageio::write_image(o.output, out);
}

void run_combine(const AppOptions& o) {
  const imageio::Image base = read_input(o.input);
  const imageio::Image detail = read_input(o.detail);
  wa::CombineSettings s;
  s.params = resolve_params(o, 5);
  s.space = wa::parse_colour_space(o.space.empty() ? "ycc" : o.space);
  s.fit = wa::parse_fit(o.fit);
  check_levels(o.input, s.params, base);
  const auto names = wa::channel_names(base.channels, s.space);
  for (const std::string& b : o.bands) s.bands.push_back(wa::parse_rule_spec(b, names, s.params.levels));
  auto engine = make_engine(o);
  announce(o, *engine);
  if (!o.quiet && (detail.width != base.width || detail.height != base.height))
    std::cerr << "dwtool: note: the detail image (" << detail.width << "x" << detail.height << ") is "
              << (s.fit == wa::Fit::Resize ? "resized" : "tiled") << " to the base's " << base.width << "x"
              << base.height << '\n';
  const auto t0 = Clock::now();
  const imageio::Image out = wa::combine_images(base, detail, s, *engine);
  report(o, "combine (two forwards, band rules, inverse)", t0);
  imageio::write_image(o.output, out);
}

void run_decouple(const AppOptions& o) {
  if (o.illuminance.empty()) throw std::invalid_argument("decouple needs --illuminance FILE for the illuminance image");
  const imageio::Image image = read_input(o.input);
  wa::DecoupleSettings s;
  s.params = resolve_params(o, 5);
  s.guard = o.guard;
  check_levels(o.input, s.params, image);
  if (s.params.levels < 1) throw std::invalid_argument("decouple needs at least one decomposition level (--levels)");
  auto engine = make_engine(o);
  announce(o, *engine);
  const auto t0 = Clock::now();
  const wa::DecoupledImages out = wa::decouple_image(image, s, *engine);
  report(o, "decouple", t0);
  imageio::write_image(o.illuminance, out.illuminance);
  imageio::write_image(o.output, out.decal);
}

void run_deform(const AppOptions& o) {
  if (o.head == !o.input.empty()) throw std::invalid_argument("deform needs either -i NET or --head");
  const std::string out_ext = lower_extension(o.output);
  if (out_ext != ".net" && out_ext != ".txt" && out_ext != ".ply")
    throw std::invalid_argument(o.output + ": the deformed net is written as .net/.txt (text) or .ply (PLY grid)");
  if (!o.mesh.empty() && lower_extension(o.mesh) != ".obj" && lower_extension(o.mesh) != ".ply")
    throw std::invalid_argument(o.mesh + ": the surface mesh is written as .obj or .ply");
  const wa::ControlNet net = o.head ? wa::head_control_net() : wa::read_control_net(o.input);
  const dwt::DwtParams params = resolve_params(o, 3);
  std::vector<wa::ScaleSpec> specs;
  const auto names = wa::axis_names();
  for (const std::string& b : o.bands) specs.push_back(wa::parse_scale_spec(b, names, params.levels));
  try {
    dwt::validate(params, net.columns, net.rows);
  } catch (const dwt::DwtError& e) {
    throw std::runtime_error((o.head ? std::string("the built-in head") : o.input) + ": " + e.what());
  }
  auto engine = make_engine(o);
  announce(o, *engine);
  const auto t0 = Clock::now();
  const wa::ControlNet deformed = wa::deform_net(net, params, specs, *engine);
  report(o, "deform", t0);
  const wa::SurfaceMesh surface = wa::tessellate(deformed, o.subdivisions);
  if (const std::string problem = wa::mesh_problem(surface); !problem.empty())
    throw std::runtime_error("the deformed surface is not a valid mesh: " + problem);
  imageio::Image picture;
  if (!o.picture.empty()) {
    const auto ops = wa::scale_operations(specs, 0, net.columns, net.rows, params);
    picture = wa::stack_pictures(wa::render_mesh(surface, 360, 400),
                                 wa::band_layout_picture(ops, net.columns, net.rows, 160));
  }
  if (out_ext == ".ply")
    wa::write_control_net_ply(o.output, deformed);
  else
    wa::write_control_net_text(o.output, deformed);
  if (!o.mesh.empty()) wa::write_mesh(o.mesh, surface);
  if (!o.picture.empty()) imageio::write_image(o.picture, picture);
}

}  // namespace

std::vector<CLI::App*> add_app_commands(CLI::App& app, AppOptions& o) {
  const std::string band_help = "[CHANNEL:]BAND=OP, repeatable; BAND: LL, *, LEVEL:HL|LH|HH|* (LEVEL 1 = finest, or *)";
  CLI::App* edit = app.add_subcommand("edit", "Scale, zero or keep subbands: forward DWT, band operation, inverse");
  edit->add_option("-i,--input", o.input, "Image")->required();
  edit->add_option("-o,--output", o.output, "Edited image (the input's sample format)")->required();
  edit->add_option("--space", o.space, "rgb|ycc (channels R,G,B or Y,Cb,Cr; grey: Y)")->default_str("rgb");
  edit->add_option("--band", o.bands, band_help + "; OP: a factor, zero or keep");
  add_engine_options(*edit, o);

  CLI::App* combine = app.add_subcommand("combine", "Style an image with another's detail (thesis Figure 4.10)");
  combine->add_option("-i,--input", o.input, "Base image (its lowest band and chroma are kept)")->required();
  combine->add_option("--detail", o.detail, "Image whose detail bands are merged in")->required();
  combine->add_option("-o,--output", o.output, "Combined image")->required();
  combine->add_option("--space", o.space, "rgb|ycc")->default_str("ycc");
  combine->add_option("--fit", o.fit, "How a detail image of another size is fitted: resize (bilinear) or tile")
      ->capture_default_str();
  combine->add_option(
      "--band", o.bands,
      band_help + "; OP: " + std::string(wa::rule_names()) + " (defaults: Y detail bands max, everything else base)");
  add_engine_options(*combine, o);

  CLI::App* decouple = app.add_subcommand("decouple", "Texture-illuminance decoupling (thesis Figure 4.11)");
  decouple->add_option("-i,--input", o.input, "Photograph")->required();
  decouple->add_option("-o,--output", o.output, "Decal: the photograph divided by its illuminance")->required();
  decouple->add_option("--illuminance", o.illuminance, "Illuminance: the inverse DWT of the lowest band alone")
      ->required();
  decouple->add_option("--guard", o.guard, "Divide by at least this fraction of the sample range")
      ->capture_default_str();
  add_engine_options(*decouple, o);

  CLI::App* deform = app.add_subcommand("deform", "Deform a control net in the wavelet domain (thesis Figure 4.9)");
  deform->add_option("-i,--input", o.input, "Control net (.net text or ASCII PLY grid; see README)");
  deform->add_flag("--head", o.head, "Use the built-in control net: the performer's procedural head");
  deform->add_option("-o,--output", o.output, "Deformed net: .net/.txt or .ply")->required();
  deform->add_option("--mesh", o.mesh, "Also write the surface (bicubic B-spline of the net) as .obj or .ply");
  deform->add_option("--subdivisions", o.subdivisions, "Surface samples per net cell, 1..64 (1: the net's quads)")
      ->capture_default_str();
  deform->add_option("--picture", o.picture, "Also render the surface and the band layout to an image (PNG)");
  deform->add_option("--band", o.bands, band_help + " with CHANNEL X, Y or Z; OP: a factor, zero or keep");
  add_engine_options(*deform, o);
  return {edit, combine, decouple, deform};
}

void run_app(const AppOptions& options) {
  switch (options.command) {
    case AppCommand::Edit:
      return run_edit(options);
    case AppCommand::Combine:
      return run_combine(options);
    case AppCommand::Decouple:
      return run_decouple(options);
    case AppCommand::Deform:
      return run_deform(options);
  }
}

}  // namespace dwtool
