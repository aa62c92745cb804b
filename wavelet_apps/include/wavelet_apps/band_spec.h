// Naming subbands on the command line: "[CHANNEL:]BAND=OPERATION", for example
//   Y:1:*=1.8    every detail band of level 1 (the finest) of channel Y, scaled by 1.8
//   2:HH=0       HH of level 2 of every channel, zeroed
//   *:HL=zero    HL of every level; "zero" is factor 0, "keep" factor 1
//   Cb:LL=keep   the lowest band (the coarsest level's LL) of Cb
//   *=0.5        every band, LL included
// BAND is LL, *, or LEVEL:ORIENTATION with LEVEL 1..levels or *, and ORIENTATION HL, LH, HH or *.
// Later specs override earlier ones where they overlap.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "dwt/band_operation.h"
#include "dwt/geometry.h"
#include "dwt/params.h"
#include "wavelet_apps/error.h"

namespace wavelet_apps {

struct BandSelector {
  int channel = -1;                             // index into the channel names; -1: every channel
  bool lowest = false;                          // the coarsest LL (then level/orientation are unused)
  int level = 0;                                // 1..levels; 0: every level
  std::optional<dwt::Orientation> orientation;  // HL, LH or HH; none: all three (and LL when `every_band`)
  bool every_band = false;                      // "*": every band, LL included

  bool matches(int channel_index, const dwt::BandId& band, int levels) const;
};

// Edit: a factor per band.
struct ScaleSpec {
  std::string text;
  BandSelector where;
  float factor = 1.0f;
};

// Combine: how a band of the base (first) and the detail (second) image are merged.
struct RuleSpec {
  std::string text;
  BandSelector where;
  dwt::BandRule rule = dwt::BandRule::First;
  float first_factor = 1.0f;
  float second_factor = 1.0f;
};

// Throw AppError "band spec 'TEXT': problem" for an unknown channel or band name, a level above
// `levels`, or an operation that is not a finite number, zero or keep (combine: max, base, detail,
// sum or zero).
ScaleSpec parse_scale_spec(std::string_view text, std::span<const std::string> channels, int levels);
RuleSpec parse_rule_spec(std::string_view text, std::span<const std::string> channels, int levels);
std::string_view rule_names();  // "max|base|detail|sum|zero", for help texts

// The operations for one channel of a plane: every band of the decomposition, each with the last
// spec that matches it, else factor 1 (edit) or `fallback` (combine).
std::vector<dwt::BandOperation> scale_operations(std::span<const ScaleSpec> specs, int channel, int width, int height,
                                                 const dwt::DwtParams& params);
std::vector<dwt::BandOperation> rule_operations(std::span<const RuleSpec> specs, int channel, int width, int height,
                                                const dwt::DwtParams& params, const RuleSpec& fallback);

}  // namespace wavelet_apps
