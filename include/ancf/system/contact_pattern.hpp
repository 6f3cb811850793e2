// The iteration pattern of a model with contact (DESIGN §5): the model's own pattern plus the
// 12×12 coupling blocks of the contact element pairs that are near. Reserving every candidate
// pair instead (the first design) made the capture scene's matrix 21 % dense and put 77 % of its
// run time into KLU; here a broad phase with a margin derived from the element and shape speeds
// and a look-ahead time, with hysteresis, decides which blocks the pattern holds, and the pattern
// is rebuilt only when that set changes.
//
// Slots. Assembly writes through "assembly slots": slot s < model.pattern().nonzeros() is entry s
// of the model's own pattern (so the model's element, body, row and force slots stay valid), and
// the entries of near coupling blocks that the model's pattern lacks get the slots after it.
// position_of_slot() maps every assembly slot to its position in pattern(), the CSC pattern the
// solvers factorize.
#pragma once

#include <span>
#include <vector>

#include "ancf/core/sparsity_pattern.hpp"
#include "ancf/system/contact_data.hpp"

namespace ancf {

class Model;
struct SystemState;
struct Workspace;

/// Which coupling blocks the pattern holds.
enum class ContactPatternPolicy {
  near,  ///< the blocks of element pairs within the broad-phase margin (default)
  all,   ///< every candidate block of every pair, fixed (the first design; for comparison)
};

struct ContactPatternOptions {
  ContactPatternPolicy policy = ContactPatternPolicy::near;
  /// Geometric part of the margin, in units of the pair's reach (cable radius, or the sum of the
  /// two radii for cable–cable pairs) [-]: blocks whose boxes come this close count as near even
  /// at rest, so that pairs resting side by side do not enter and leave on round-off.
  double reach_factor = 2.0;
  /// Kinematic part: the margin grows by look_ahead × horizon × (speed bound of both sides), the
  /// distance the two sides can close in look_ahead horizons [-].
  double look_ahead = 2.0;
  /// Hysteresis: a near block leaves only when its boxes are farther apart than leave_factor
  /// times the margin at which it would enter (> 1).
  double leave_factor = 2.0;
};

/// Slot tables of the coupling blocks the current pattern holds, read by the contact sampling
/// (assembly.cpp). Block k of a pair occupies blocks[2k] (rows of side a, columns of side b) and
/// blocks[2k + 1] (the transpose block), column-major assembly slots.
struct ContactCoupling {
  /// Per cable–shape pair (empty unless the shape is on a body): per candidate element (local
  /// index), its block index k or −1 (not near).
  std::vector<std::vector<Index>> shape_block;
  /// Per cable–cable pair: per element pair (local i·count_b + j), its block index k or −1.
  std::vector<std::vector<Index>> cable_block;
  std::vector<BlockSlots> blocks;
};

/// Counters of a ContactPattern (cumulative).
struct ContactPatternStatistics {
  long updates = 0;         ///< update() calls
  long rebuilds = 0;        ///< pattern changes (each needs a symbolic analysis by the solver)
  long blocks_entered = 0;  ///< coupling blocks that became near
  long blocks_left = 0;     ///< coupling blocks that stopped being near
  Index near_blocks = 0;    ///< coupling blocks in the current pattern
  Index most_nonzeros = 0;  ///< largest pattern().nonzeros() so far
};

/// Ownership: keeps a reference to `model`, which must outlive it. Not thread-safe.
class ContactPattern {
 public:
  explicit ContactPattern(const Model& model, ContactPatternOptions options = {});

  /// Re-decide which blocks are near at `state` for matrices that serve about `horizon` seconds
  /// (≥ 0) and rebuild the pattern if that set changed; returns true then. The element boxes in
  /// `ws` are refreshed on the way. Allocates only when the pattern changes. With the `all`
  /// policy, or no candidate coupling blocks, it never changes.
  bool update(const SystemState& state, double horizon, Workspace& ws);

  /// CSC pattern of the (n + m)² iteration matrix: the model's pattern ∪ the near coupling blocks.
  [[nodiscard]] const SparsityPattern& pattern() const { return pattern_; }
  /// Number of assembly slots (model.pattern().nonzeros() + the coupling entries it lacks).
  [[nodiscard]] Index slot_count() const { return static_cast<Index>(position_.size()); }
  /// Position in pattern() of each assembly slot.
  [[nodiscard]] std::span<const Index> position_of_slot() const { return position_; }
  /// Row and column of each assembly slot.
  [[nodiscard]] std::span<const Index> slot_rows() const { return rows_; }
  [[nodiscard]] std::span<const Index> slot_columns() const { return columns_; }
  /// True when assembly slots and pattern() positions coincide (no coupling entries beyond the
  /// model's own pattern): the matrix can then be assembled in place.
  [[nodiscard]] bool identity() const { return identity_; }

  [[nodiscard]] const ContactCoupling& coupling() const { return coupling_; }
  [[nodiscard]] const ContactPatternStatistics& statistics() const { return stats_; }
  [[nodiscard]] const ContactPatternOptions& options() const { return options_; }

 private:
  void rebuild();

  const Model& model_;
  ContactPatternOptions options_;
  bool has_candidates_ = false;
  // Near flags per candidate block (same layout as coupling_.shape_block / cable_block).
  std::vector<std::vector<char>> shape_near_, cable_near_;
  std::vector<std::vector<double>> element_speed_;  // per cable in contact, per element [m/s]
  ContactCoupling coupling_;
  SparsityPattern pattern_;
  std::vector<Index> position_, rows_, columns_;
  std::vector<std::pair<Index, Index>> extra_;  // (col, row) of slots beyond the model's pattern
  bool identity_ = true;
  ContactPatternStatistics stats_;
};

}  // namespace ancf
