#pragma once
// The run's simulation decomposed in space over the ranks of MPI_COMM_WORLD
// (mpi::DistributedSimulation, docs/explanation/scaling.md): every figure of the whole run reduced over
// the ranks in rank order. Every rank writes its own rows of each frame and of each checkpoint
// through MPI-IO (the serial layouts), a frame's fragment labels from a distributed union-find.
#include <optional>

#include "../run_backend.hpp"
#include "shard/mpi/distributed_simulation.hpp"

namespace shard::driver::detail {

class MpiBackend final : public RunBackend {
 public:
  MpiBackend();
  int rank() const override { return rank_; }
  int ranks() const override { return ranks_; }
  Checkpoint read_restart(const std::filesystem::path& checkpoint) const override;
  void on_root(const std::function<void()>& work) const override;
  void on_all(const std::function<void()>& work) const override;
  void barrier() const override;
  RunWriterAccess run_file_access() const override;
  ScenePart instantiate(const Scene& scene, const PluginHost& host,
                        const std::function<void(const std::string&)>& log) const override;
  void start(const Scene& scene, ScenePart& part, const SimulationState* from) override;
  void add_notes(RunMetadata& meta, bool restarting) const override;
  std::string where() const override;

  Simulation& local() override { return dist_->local(); }
  bool owns(std::size_t k) const override { return dist_->owns(k); }
  void step() override;
  const std::vector<WallContactBegun>& wall_contacts_begun() const override { return begun_; }
  const RunState::Whole* whole() const override { return &whole_; }

  Energies energies() const override { return dist_->energies(); }
  std::size_t bond_count() override;
  std::int64_t bonds_broken() const override { return dist_->bonds_broken(); }
  std::size_t contact_count() const override { return dist_->contact_count(); }
  std::int64_t wall_contacts_begun_anywhere() const override { return dist_->wall_contacts_begun_anywhere(); }
  std::vector<BondBreakEvent> take_new_break_events() override;
  void write_checkpoint(Checkpoint& loop, const std::filesystem::path& file) const override;
  double deformation_kinetic_energy() const override;
  void write_frame(RunWriter& writer, RunState& state, const std::function<void()>& before_frame) override;

  std::vector<double> sum_over_ranks(const std::vector<double>& mine) const override {
    return dist_->sum_over_ranks(mine);
  }
  std::vector<double> gather_over_ranks(const std::vector<double>& mine) const override {
    return dist_->gather_over_ranks(mine);
  }
  bool any_rank(bool mine) const override { return dist_->any_rank(mine); }

 private:
  int rank_ = 0, ranks_ = 1;
  std::optional<mpi::DistributedSimulation> dist_;
  std::vector<WallContactBegun> begun_;
  std::size_t events_written_ = 0;  // break events handed to the run file
  RunState::Whole whole_;
};

}  // namespace shard::driver::detail
