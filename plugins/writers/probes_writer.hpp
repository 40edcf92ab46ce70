// "probes" writer: one CSV row per call (the host schedules it with the common
// "every"/"every_steps" keys) with
//  - SPH-interpolated fields at points (Shepard, see sph_sampler.hpp): any
//    scalar field, a vector field's components (NAME -> NAME_x, NAME_y[, NAME_z]),
//    one component (NAME_x) or the magnitude (NAME_mag);
//  - wave gauges: free-surface elevation along vertical lines;
//  - integral quantities of the fluid: mass, kinetic and potential energy,
//    particle count, particles removed, peak speed;
//  - forces: the fluid's pressure force on wall bodies (the SPH pair force
//    between fluid and wall particles, summed over the body's wall particles)
//    and the external (coupling) force on each block;
//  - wall pressure sensors: the fluid's pressure force on the wall particles
//    behind a patch of a wall's surface, normal component, divided by the
//    patch's area (a pressure transducer mounted in the wall). With dynamic
//    boundary particles this, not the fluid pressure interpolated next to
//    the wall, is the load the wall carries: the first wall layer holds the
//    fluid off at a gap with its own (much higher) pressure, and the fluid
//    pressure within a kernel support of the wall falls short of the load.
// The file is append-only: '#' comment lines, a header row, then one row per
// frame written with one write(2); a failed write is cut back so the file
// always ends with a complete row. Layout: docs/output-formats.md.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "breaker_analysis.hpp"
#include "file_io.hpp"
#include "sph_sampler.hpp"
#include "talus/params.hpp"
#include "talus/particles.hpp"
#include "talus/sph/fluid_terms.hpp"
#include "talus/writer.hpp"

namespace talus::writers {

class ProbesWriter final : public Writer {
 public:
  static ParamSet describe();
  explicit ProbesWriter(const ParamValues& params);

  void check(const World& world) const override;
  void open(const OutputContext& context, const World& world) override;
  void write(const World& world) override;
  void close(const World& world) override;
  std::vector<std::string> files() const override;
  std::vector<std::string> series(const World& world) const override;
  std::vector<std::string> result_names() const override;
  std::vector<WriterResult> results() const override { return results_; }
  bool writes_on_every_rank() const override { return true; }

  // The header row (column names) once open() ran, for tests and tools.
  const std::vector<std::string>& columns() const { return names_; }

 private:
  enum class Quantity { mass, kinetic_energy, potential_energy, particles, removed, max_speed };
  struct PointColumn {
    std::size_t point;
    std::string field;
    bool vector;
    int component;  // 0..2, or 3 = magnitude (vectors)
  };
  struct Gauge {
    std::string name;
    Vec3 at;
    bool warned = false;  // its dry line was reported
    bool air = false;     // a surf gauge of the waves section: also records the air under its surface and its surface speed
    double surface = 0.0;  // the highest free surface on its line, of the row being written
    std::vector<Vec3> samples;  // along its line, from the top down (line_samples)
  };
  struct WallSensor {
    std::string name;
    Vec3 at, normal;                // a point on the wall surface; unit normal into the fluid
    std::vector<Index> particles;   // wall particles behind the patch (indices in world.boundary; this rank's)
    std::uint64_t particle_count = 0;  // over all ranks
    double area = 0.0;              // m^2 (m in 2D): surface-layer particles times dp^(dim-1)
  };

  // Everything open() does short of the file: resolves bodies, sensors and
  // columns against the world; throws InputError on what does not fit.
  void prepare(const World& world);
  void choose_vertical(const World& world);
  void resolve_columns(const World& world);
  std::string comment_lines(const OutputContext& context, const World& world) const;
  // Bytes of an existing file to keep on resume (comments, header, rows up to
  // `step`); 0 to start afresh.
  std::size_t resume_bytes(const std::string& header, std::uint64_t step, std::uint64_t& last_step, bool& rows) const;
  double integral(Quantity q, const World& world) const;
  std::vector<WriterResult> bed_change() const;
  // The fluid's force on a wall body, over the wall particles this rank owns.
  Vec3 wall_force(int body, const World& world, const SphSampler& fluid) const;
  // The fields the wall force reads, looked up once per row.
  struct ForceFields {
    explicit ForceFields(const World& world);
    ForceFields(const ForceFields&) = delete;  // `fluid` points into `inv_rho`
    ForceFields& operator=(const ForceFields&) = delete;
    std::span<const Vec3> xa;
    std::span<const double> ma, rhoa, pa;
    std::vector<double> inv_rho;  // 1/rho of the fluid particles
    // In double, where the stores keep them in float (mixed precision).
    std::vector<double> mass_wide, pressure_wide, wall_mass_wide, wall_density_wide, wall_pressure_wide;
    sph::Neighbours fluid;        // the fluid as the solver's pressure term reads it
  };
  // The pressure force of the fluid (bound to `fluid`) on wall particle a.
  Vec3 particle_force(std::size_t a, const ForceFields& fields, const SphSampler& fluid) const;
  void select_sensor_particles(const World& world);
  double sensor_pressure(const WallSensor& sensor, const World& world, const SphSampler& fluid) const;
  void put_air_below(const World& world);
  void put_surface_speed(const World& world);

  ParamValues params_;
  std::vector<Vec3> points_;
  std::vector<std::string> point_names_;
  std::vector<Gauge> gauges_, bed_gauges_;
  // The fill fraction of one material's particles alone (bed gauges; run-up over a bank).
  struct MaterialSampler {
    int material = -1;  // -1: not used
    SphSampler sampler;
    std::vector<double> volume;  // V_j for that material's particles, 0 for the others
    void configure(const World& world, const ParamValues& params, const char* key);
    void bind(const ParticleStore& fluid, std::span<const double> all_volumes);
  };
  MaterialSampler bed_;
  std::optional<std::array<Vec3, 2>> runup_line_;
  SlopeLine runup_;  // its samples
  MaterialSampler runup_wet_;  // unused: every fluid particle is wet
  bool bed_change_ = true;  // two bed gauges or more: the eroded and deposited cross-section
  std::vector<Quantity> integrals_;
  bool block_forces_ = false;
  bool material_masses_ = false;
  std::vector<int> wall_bodies_;  // scene body indices
  std::vector<WallSensor> sensors_;
  double sensor_size_ = 0.0;      // m; 0: the wall particle spacing
  std::size_t sensor_wall_size_ = 0;  // world.boundary.size() when the sensors' particles were selected
  double gauge_step_ = 0.0, gauge_threshold_ = 0.5;
  bool wire_gauges_ = false;  // the gauges read as wire gauges (wire_elevation), not the highest surface
  int vertical_ = 2;
  double up_ = 1.0;  // +1: up is +vertical_ (gravity along -vertical_)
  double top_ = 0.0, bottom_ = 0.0;  // the gauge lines' ends along vertical_

  std::vector<PointColumn> point_columns_;
  std::vector<std::string> names_, units_;
  std::size_t block_count_ = 0;
  std::optional<BreakerAnalysis> waves_;
  std::vector<WriterResult> results_;
  std::string path_, results_path_;
  LineFile file_;
  SphSampler sampler_;        // the fluid particles this rank owns: each counted once over the ranks
  SphSampler force_sampler_;  // on several ranks, with the halo: a wall particle's fluid neighbours
  std::vector<double> volume_;
  // Fields the store keeps in float (mixed precision), widened to double for one frame.
  std::vector<double> wide_, wide_other_;
  std::vector<Vec3> wide_vectors_;
  std::vector<double> shares_;  // this rank's share of every sum in a row, then the sums over the ranks
  bool writes_file_ = true;     // rank 0
  std::vector<Neighbour> neighbours_;
  std::string row_;
  bool have_last_step_ = false;
  std::uint64_t last_step_ = 0;
};

}  // namespace talus::writers
