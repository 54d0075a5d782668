#pragma once
// The run's simulation whole in this process: every reduction is the identity.
#include <memory>

#include "run_backend.hpp"

namespace shard::driver::detail {

class SerialBackend final : public RunBackend {
 public:
  int rank() const override { return 0; }
  int ranks() const override { return 1; }
  Checkpoint read_restart(const std::filesystem::path& checkpoint) const override;
  void on_root(const std::function<void()>& work) const override { work(); }
  void on_all(const std::function<void()>& work) const override { work(); }
  void barrier() const override {}
  RunWriterAccess run_file_access() const override { return {}; }
  ScenePart instantiate(const Scene& scene, const PluginHost& host,
                        const std::function<void(const std::string&)>& log) const override;
  void start(const Scene& scene, ScenePart& part, const SimulationState* from) override;
  void add_notes(RunMetadata&, bool) const override {}
  std::string where() const override { return {}; }

  Simulation& local() override { return *sim_; }
  bool owns(std::size_t) const override { return true; }
  void step() override;
  const std::vector<WallContactBegun>& wall_contacts_begun() const override { return begun_; }
  const RunState::Whole* whole() const override { return nullptr; }

  Energies energies() const override { return sim_->energies(); }
  std::size_t bond_count() override { return sim_->bonds().size(); }
  std::int64_t bonds_broken() const override { return sim_->bonds_broken(); }
  std::size_t contact_count() const override { return sim_->contact_count(); }
  std::int64_t wall_contacts_begun_anywhere() const override { return static_cast<std::int64_t>(begun_.size()); }
  std::vector<BondBreakEvent> take_new_break_events() override { return sim_->take_new_break_events(); }
  void write_checkpoint(Checkpoint& loop, const std::filesystem::path& file) const override;
  double deformation_kinetic_energy() const override;
  void write_frame(RunWriter& writer, RunState& state, const std::function<void()>& before_frame) override;

  std::vector<double> sum_over_ranks(const std::vector<double>& mine) const override { return mine; }
  std::vector<double> gather_over_ranks(const std::vector<double>& mine) const override { return mine; }
  bool any_rank(bool mine) const override { return mine; }

 private:
  std::unique_ptr<Simulation> sim_;
  std::vector<WallContactBegun> begun_;
};

}  // namespace shard::driver::detail
