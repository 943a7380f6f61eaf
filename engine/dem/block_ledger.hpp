#pragma once
// The energy ledger of a step, per block of particles (dem/dem_solver.hpp, EnergyLedger): the
// passes over contacts add their losses through this, block by block.
#include <cstddef>

#include "core/threads.hpp"
#include "dem/contact_law.hpp"
#include "dem/dem_solver.hpp"

namespace fluidbed {

// Adds a sequence of amounts, which comes in particle order, to the ledgers of the particles'
// blocks: summed locally, stored when the block changes (and at the end).
class BlockLedger {
 public:
  explicit BlockLedger(EnergyLedger* blocks) : blocks_(blocks) {}
  BlockLedger(const BlockLedger&) = delete;
  BlockLedger& operator=(const BlockLedger&) = delete;
  ~BlockLedger() { flush(); }
  void add(std::size_t particle, double gas_work, const ContactLoss& loss) {
    const std::size_t b = particle / kParticleBlock;
    if (b != block_) {
      flush();
      block_ = b;
    }
    sum_.gas_work += gas_work;
    sum_.dashpot += loss.dashpot;
    sum_.friction += loss.friction;
  }

 private:
  void flush() {
    if (block_ != kNone) blocks_[block_] += sum_;
    sum_ = EnergyLedger{};
  }
  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  EnergyLedger* blocks_;
  std::size_t block_ = kNone;
  EnergyLedger sum_;
};

}  // namespace fluidbed
