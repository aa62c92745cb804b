// Pictures for the deformation example (thesis Figure 4.9): a shaded view of a surface drawn by a
// small software rasteriser (orthographic, z-buffered, Lambert shading), and the subband layout
// coloured by each band's factor: grey unscaled, red scaled up, blue scaled down.
#pragma once

#include <span>

#include "dwt/band_operation.h"
#include "imageio/image.h"
#include "wavelet_apps/control_net.h"

namespace wavelet_apps {

// An 8-bit RGB picture of `mesh` seen from the front (+Z toward the viewer, +Y up) turned by
// `yaw_degrees` about Y, fitted into width x height on a white background.
imageio::Image render_mesh(const SurfaceMesh& mesh, int width, int height, float yaw_degrees = 25.0f);

// An 8-bit RGB picture of the Mallat layout of a net of `columns` x `rows` scaled to `size` pixels
// wide, each band filled by its factor's colour (the first factor of `ops`), bands outlined.
imageio::Image band_layout_picture(std::span<const dwt::BandOperation> ops, int columns, int rows, int size);

// `bottom` centred below `top` on white: one picture of both.
imageio::Image stack_pictures(const imageio::Image& top, const imageio::Image& bottom);

}  // namespace wavelet_apps
