#pragma once
#include <memory>
#include <span>
#include <string>

#include "dwt/backend.h"
#include "dwt/band_operation.h"
#include "glcontext/context.h"

namespace dwt_gpu {

// The GPU's stage split (dwt/backend.h): its context and shader are paid once per backend.
using GpuTimings = dwt::DeviceTimings;

// The thesis' method (chapter 4.4-4.6): float32 textures, two framebuffers swapping roles after each
// pass, one quad per pass over the current low-pass region, and one fragment shader that looks up
// an indirect address table (boundary-extended address, filter selector, base position) and
// convolves. Forward and inverse use the same shader with different tables and kernel banks.
// Float kernels only; the reversible 5/3 stays on the CPU (supports() says so, and the integer
// entry points throw dwt::DwtError).
class GpuBackend final : public dwt::DwtBackend {
 public:
  // Creates the context lazily on first use unless `eager` is set; platform from GPUJ2K_GL when Auto.
  explicit GpuBackend(glc::Platform platform = glc::Platform::Auto, bool eager = false);
  // Adopts a context the caller made (for example with glc::Context::create_hardware()) and
  // compiles the shader at once; its creation time is the caller's to report.
  explicit GpuBackend(std::unique_ptr<glc::Context> context);
  ~GpuBackend() override;

  std::string name() const override;  // "gpu fragment shaders (<renderer>)"
  bool supports(dwt::KernelId kernel) const override;

  void forward(dwt::PlaneSpan<float> plane, const dwt::DwtParams& params) override;
  void inverse(dwt::PlaneSpan<float> plane, const dwt::DwtParams& params) override;
  void forward(dwt::PlaneSpan<std::int32_t> plane, const dwt::DwtParams& params) override;
  void inverse(dwt::PlaneSpan<std::int32_t> plane, const dwt::DwtParams& params) override;

  // Thesis 4.7's interactive editing with the coefficients kept on the GPU: forward-transforms
  // `first` (and `second` when it has data, else no second plane is used), applies `ops` as one
  // fragment pass (a quad per band rectangle; rectangles must not overlap, samples outside all of
  // them are kept), inverse-transforms, and reads the result back into `first` once. Nothing is
  // read back in between. Computes what forward, dwt::apply_band_operations and inverse compute.
  // Timings: upload (both planes), compute (transforms and band pass), download.
  void process_bands(dwt::PlaneSpan<float> first, dwt::PlaneSpan<const float> second, const dwt::DwtParams& params,
                     std::span<const dwt::BandOperation> ops);

  // The GL renderer line (renderer | version | platform); creates the context if needed.
  std::string renderer();
  const GpuTimings& last_timings() const { return timings_; }
  const dwt::DeviceTimings* device_timings() const override { return &timings_; }
  // Unbinds the context from the calling thread, so that another thread may use this backend next
  // (a context is current on one thread at a time; each use makes it current where it runs).
  void release_context() noexcept;

 private:
  struct State;
  void ensure_ready();
  void prepare(std::unique_ptr<glc::Context> context);
  void transform(dwt::PlaneSpan<float> plane, const dwt::DwtParams& params, bool inverse);
  // The stages both entry points are made of. Between them the data lives in pixel buffer 0.
  void begin(const dwt::DwtParams& params, int width, int height);
  void upload(dwt::PlaneSpan<const float> plane);
  void run_levels(const dwt::DwtParams& params, bool inverse);
  void run_band_pass(std::span<const dwt::BandOperation> ops, bool reads_second);
  void download(dwt::PlaneSpan<float> plane);

  glc::Platform platform_;
  std::unique_ptr<State> state_;
  GpuTimings timings_;
};

}  // namespace dwt_gpu
