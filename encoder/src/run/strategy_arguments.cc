#include "encoder/src/run/strategy_arguments.h"

#include <cstdio>

#include "encoder/src/train/random_start_schedule.h"

namespace m4d {

void ApplyStrategy(const std::string& name, KeyframeTrainingOptions* options) {
  if (!name.empty()) ParseStrategyName(name, &options->strategy);
}

void PrintTrainingReport(const KeyframeTrainingReport& report) {
  for (const KeyframeStart& s : report.starts) {
    std::printf("%-28s %s: %zu points%s\n", "start", s.name.c_str(), s.points,
                s.taken ? " (taken)" : ", too few");
  }
  if (report.random_start_schedule) {
    const RandomStartSchedule schedule;
    std::printf("%-28s the random start's: position and scale rates x%g and x%g, %s\n", "schedule",
                schedule.position_rate, schedule.scaling_rate,
                schedule.opacity_reset ? "opacity reset" : "no opacity reset");
  }
  std::printf("%-28s %10s %10s %10s %10s\n", "run, per tenth", "iteration", "Gaussians", "loss",
              "PSNR");
  for (const TrainingTenth& t : report.tenths) {
    std::printf("%-28s %10d %10zu %10.4f %10.2f\n", "", t.iteration, t.gaussians, t.loss, t.psnr);
  }
  const StrategyCounts& c = report.counts;
  std::printf(
      "%-28s cloned %zu, split %zu, pruned %zu, relocated %zu, added %zu; "
      "largest removal %.1f %%\n",
      "densification", c.cloned, c.split, c.pruned, c.relocated, c.added,
      100.0 * report.largest_removal);
}

}  // namespace m4d
