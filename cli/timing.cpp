#include "timing.h"

#include "base/json_string.h"

namespace cli {

using base::json_string;

double stage_sum(std::span<const TimedStage> stages) {
  double sum = 0;
  for (const auto& stage : stages) sum += stage.second;
  return sum;
}

void print_timing(const std::string& mode, const TimingReport& r) {
  const double sum = stage_sum(r.stages);
  if (mode == "json") {
    std::string json = "{\"dwt\": " + json_string(r.dwt_backend) + ", \"dwt_reason\": " + json_string(r.dwt_reason) +
                       ", \"threads\": " + std::to_string(r.threads) + ", \"stages_ms\": {";
    for (std::size_t i = 0; i < r.stages.size(); ++i)
      json += (i ? ", " : "") + json_string(r.stages[i].first) + ": " + std::to_string(r.stages[i].second);
    json += "}";
    for (const auto& [key, count] : r.counts) json += ", " + json_string(key) + ": " + std::to_string(count);
    json += ", \"sum_ms\": " + std::to_string(sum) + ", \"total_ms\": " + std::to_string(r.measured_ms) + "}";
    std::fprintf(stderr, "%s\n", json.c_str());
    return;
  }
  std::fprintf(stderr, "%s: timing in ms, DWT on %s (%s), %d threads\n", r.tool.c_str(), r.dwt_backend.c_str(),
               r.dwt_reason.c_str(), r.threads);
  for (const auto& [name, ms] : r.stages) std::fprintf(stderr, "  %-22s %10.2f\n", name, ms);
  std::fprintf(stderr, "  %-22s %10.2f\n  %-22s %10.2f\n", "sum of stages", sum, "total (measured)", r.measured_ms);
}

}  // namespace cli
