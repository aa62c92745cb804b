#pragma once

namespace codec {

// Where the irreversible 9/7 transform runs, for the encoder and the decoder alike. Cpu: the
// lifting backend. Gpu: any GL context, software renderers included, or a failure. Auto: a
// hardware GPU where its calibrated costs beat the CPU for the image size, never a software
// rasteriser. The reversible 5/3 always runs on the CPU.
enum class DwtDevice { Cpu, Gpu, Auto };

}  // namespace codec
