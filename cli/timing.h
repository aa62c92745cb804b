#pragma once
// --timing for j2kenc and j2kdec: a stage table, or one JSON object, on stderr.
#include <cstddef>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace cli {

// One row of the table: the stage's name (also its JSON key) and its milliseconds.
using TimedStage = std::pair<const char*, double>;

struct TimingReport {
  std::string tool;  // "j2kenc", "j2kdec": the text table's first word
  std::string dwt_backend, dwt_reason;
  int threads = 0;
  std::span<const TimedStage> stages;  // in data-flow order
  double measured_ms = 0;              // the whole run, measured around it
  // Whole-number facts after the stages in the JSON (the encoder's recoded blocks); the text form
  // leaves them to the caller.
  std::vector<std::pair<std::string, std::size_t>> counts;
};

// `mode` "text": "TOOL: timing in ms, DWT on B (why), N threads", one line per stage, the sum of
// stages and the measured total. "json": {"dwt", "dwt_reason", "threads", "stages_ms": {...},
// counts..., "sum_ms", "total_ms"}.
void print_timing(const std::string& mode, const TimingReport& report);

// The sum of the stages' milliseconds.
double stage_sum(std::span<const TimedStage> stages);

}  // namespace cli
