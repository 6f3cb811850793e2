// Runaway work refused before it starts (issue 17): the memory a scene's mesh would need against
// the machine's memory, and the number of steps a run implies against a bound the user can raise.
#pragma once

#include "ancf/io/scene.hpp"

namespace ancf {

/// Peak memory of `ancf run` per cable element [bytes], measured (peak RSS, /usr/bin/time) on a
/// pinned bending cable of 1 000 and 10 000 elements: IDA 21.9 kB/element (GGL system of twice
/// the size, BDF history), generalized-α 10.3 kB, `ancf check` 4.8 kB. The larger, rounded up.
inline constexpr double kRunBytesPerCableElement = 24e3;

/// Physical memory of this machine [bytes] (sysconf), or 0 if it cannot be read.
[[nodiscard]] double machine_memory_bytes();

/// Throws ModelError if `elements` cable elements in all need more than `budget_bytes` to run
/// (kRunBytesPerCableElement each). `budget_bytes` ≤ 0 means machine_memory_bytes().
void require_memory_for_elements(double elements, double budget_bytes);

/// Fewest steps a run of `settings` to t_end takes with output every `output_interval`:
/// generalized-α max(t_end/h, output times), IDA max(t_end/max_step, output times) (IDA stops
/// at every output time; without max_step only the output times bound it from below).
[[nodiscard]] double minimum_step_count(const IntegratorSettings& settings, double output_interval);

/// Default of `--max-steps`: 10⁷ steps (the capture example takes 4·10⁴; 10⁷ generalized-α steps
/// of the benchmark pendulum take about 10 minutes).
inline constexpr double kDefaultMaxSteps = 1e7;

/// Throws ModelError naming the count, the settings it comes from and the option that raises
/// the bound if minimum_step_count(settings, output_interval) exceeds max_steps.
void require_bounded_steps(const IntegratorSettings& settings, double output_interval,
                           double max_steps);

/// What a run checks before it starts (`ancf run` after its command-line overrides, the Python
/// module): a generalized-α step not above t_end ("--step exceeds t_end"), h_max not below h_min,
/// and require_bounded_steps. Throws ModelError.
void require_runnable(const IntegratorSettings& settings, double output_interval, double max_steps);

}  // namespace ancf
