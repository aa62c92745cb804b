// Which hardware GPUs and drivers a machine has, read without loading EGL or making a context.
#pragma once

#include <filesystem>
#include <string>

namespace glc {

// A line naming the machine's GPU device nodes with their hardware and driver, read from the
// kernel's records of them: NVIDIA's /proc/driver/nvidia (driver version, each GPU's model), the
// DRM nodes' /sys/class/drm/<node>/device (PCI vendor and device, kernel driver) and WSL's
// /dev/dxg, the last two with the kernel release. Empty where the system has no GPU device node.
//
// It serves as the key of measurements made on those GPUs: reading it takes a few small file
// reads, where the GL_RENDERER string needs the driver loaded and a context made, some 60-70 ms
// on an NVIDIA H200 (which is how long `--dwt auto` used to spend to learn from its cache that the
// CPU was faster). A driver update changes the line, so measurements are taken again. `root`
// stands for "/" (tests give a made-up tree).
std::string hardware_gpu_fingerprint(const std::filesystem::path& root = "/");

}  // namespace glc
