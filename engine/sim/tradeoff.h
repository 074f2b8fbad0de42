// The measured trade of speed for accuracy (docs/architecture.md, "The measured trade"): a
// converged reference run of a scene, then a sweep of its knobs (substep, integrator, rk45
// tolerance, mesh resolution), each run's error against the reference at matched frame times
// and its cost. `pbm bench tradeoff` writes it as CSV and a plot; the studio's trade panel shows
// the same numbers for the open scene. Figures' segments count as centres; later subsystems add
// their error columns here: the liquids' volume, centre, front and surface height.
//
// The liquids' knobs (resolution, CFL, advection, pressure solver, beta_0, epsilon, marker
// density) are swept one at a time around the scene's setting: a factorial of seven knobs would
// be thousands of runs.
//
// The figures' physics knobs (contact stiffness, restitution, controller gains, t_s) change the
// answer, not only its error: each of their settings gets a converged reference of its own, its
// points are measured against that, and how far its reference lies from the scene's own is
// reported apart (TradeoffPoint::physics_centre), so a user sees both what a knob costs and what
// it changes.
#pragma once

#include <algorithm>
#include <atomic>
#include <optional>
#include <string>
#include <vector>

#include "core/function_ref.h"
#include "scene/scene.h"

namespace pbm {

// One point of the sweep: the knobs as set.
struct TradeoffSetting {
  Real dt = 0;  // solver.dt [s]
  IntegratorKind integrator = IntegratorKind::euler;
  Real tolerance = 0;    // solver.tolerance (rk45)
  Real resolution = 1;   // rings and segments of every body, times this
  bool current = false;  // the scene's own setting
  // tessellation.contact of every local body; unset: each body's own
  std::optional<ContactQuadrature> contact;
  // The figures' physics (FigureDef, ControllerDef; 1 and unset: the scene's own):
  // every figure's contact_stiffness times this, its contact_damping times its square root
  // (the contact's damping ratio kept, as MuJoCo's solref keeps dampratio);
  Real stiffness = 1;
  std::optional<Real> restitution;  // every figure's e (15.2)
  // PD and stable-PD kp times this and kd times its square root (the servo's damping ratio
  // kept), MRAC's alpha and beta (15.16), (15.17) times this; the mocap servos' alike;
  Real gains = 1;
  Real settling = 1;  // MRAC's t_s times this (15.11): lambda = 4 / t_s
  // Every liquid's knobs (LiquidDef; 1, 0 and unset: the scene's own): its cells per axis times
  // liquid_resolution (a 2D liquid's thin axis stays one cell thick), cfl, advection, pressure
  // solver, relaxation beta_0 (16.7), tolerance epsilon and markers_per_axis.
  Real liquid_resolution = 1;
  Real cfl = 0;
  std::optional<LiquidAdvection> advection;
  std::optional<PressureSolver> pressure_solver;
  Real relaxation = 0;
  Real epsilon = 0;
  int markers_per_axis = 0;
  // The physics this setting simulates: its stiffness, restitution, gains and settling.
  bool same_physics(const TradeoffSetting& other) const;
  bool scenes_physics() const;
  std::string label() const;
};

// Errors against the reference over the run's frames (largest over frames and bodies) and cost.
struct TradeoffPoint {
  TradeoffSetting setting;
  bool ok = false;
  std::string message;      // why the run failed
  double wall_seconds = 0;  // stepping only (FrameStats::wall_seconds)
  long substeps = 0, evaluations = 0, retries = 0;
  Real centre_error = 0;  // |c - c_ref| [m], bodies' centres and figures' segments
  // Figures' joints: the angle of each segment's rotation from its parent against the
  // reference's [rad] (0 without figures; prismatic joints add none).
  Real joint_error = 0;
  Real shape_error = 0;           // |q_s - q_s,ref| (max norm)
  Real node_rms = -1;             // RMS of node position differences [m]; -1: other node count
  Real constraint_violation = 0;  // the run's own max |C| [m]
  Real energy_error = 0;          // |E - E_ref| / the reference's largest kinetic + elastic energy
  Real depth = 0;                 // the run's deepest contact: figures' and bodies' nodes' [m]
  // How far the converged answer of this setting's physics lies from the scene's own (both
  // references; 0 for the scene's physics): what a physics knob changes, apart from the error.
  Real physics_centre = 0;  // [m], as centre_error
  Real physics_joint = 0;   // [rad], as joint_error
  // The liquids' (0 without liquids), largest over frames and liquids against the reference:
  Real liquid_volume = 0;  // |V - V_ref| / V_ref
  Real liquid_centre = 0;  // its centre of mass [m]
  Real liquid_front = 0;   // its farthest reach along the grid's first horizontal axis [m]
  Real liquid_height = 0;  // its highest point [m]
  // No other point is both faster and more accurate (the larger of the centre errors of bodies
  // and liquids).
  bool pareto = false;
  Real accuracy_error() const { return std::max(centre_error, liquid_centre); }
};

struct TradeoffKnobs {
  std::vector<Real> dt;
  std::vector<IntegratorKind> integrators;  // rk45 runs once per tolerance
  std::vector<Real> tolerances;
  std::vector<Real> resolutions;
  // Empty or {unset}: the bodies' own.
  std::vector<std::optional<ContactQuadrature>> contacts{std::nullopt};
  // The figures' physics knobs (TradeoffSetting); empty: the scene's own ({1} and {unset}).
  std::vector<Real> stiffness;
  std::vector<std::optional<Real>> restitution;
  std::vector<Real> gains;
  std::vector<Real> settling;
  // The liquids' (TradeoffSetting), each swept alone around the scene's setting; empty: the
  // scene's own.
  std::vector<Real> liquid_resolution;
  std::vector<Real> cfl;
  std::vector<LiquidAdvection> advection;
  std::vector<PressureSolver> pressure_solver;
  std::vector<Real> relaxation;
  std::vector<Real> epsilon;
  std::vector<int> markers_per_axis;
};

struct TradeoffOptions {
  Real seconds = 2;  // simulated time of every run
  Real reference_tolerance = 1e-7;
  TradeoffKnobs knobs;
};

struct TradeoffReport {
  TradeoffSetting reference;          // of the scene's own physics
  double reference_wall_seconds = 0;  // of all references
  int references = 1;                 // one per physics setting
  std::vector<TradeoffPoint> points;
  std::vector<std::string> notes;  // knobs left out and why
  bool cancelled = false;
};

// The knobs named (dt, integrator, tolerance, resolution, contact, and the figures' stiffness,
// restitution, gains, settling) at values around the scene's: dt at 2, 1, 1/2, 1/4 times the
// scene's (at most a frame), euler, rk4 and implicit, rk45 at 1e-3, 1e-4, 1e-5, resolution 1/2,
// 1 and 2 times, contact at both rules of tessellation.contact, stiffness 1/4, 1 and 4 times,
// restitution the scene's and 0, 0.5, 1, gains and settling 1/2, 1 and 2 times. Resolution is
// left out (with a note) when a body's mass is given per node (`nodal_mass`): refining it
// changes the physics; contact, when no body is local (only local bodies have contact points);
// the figures' knobs, when no figure has what they act on. The liquids' (liquid_resolution,
// cfl, advection, pressure_solver, relaxation, epsilon, markers): resolution 1/2, 1 and 2 times,
// CFL 1, 1/2, 1/4, every advection (flip with markers only), every pressure solver, beta_0 1.2,
// 1.5, 1.9 (with the relaxation solver), epsilon 1e-3 to 1e-5, 1 to 3 markers per axis (markers
// only); left out with a note without a liquid. Throws pbm::Error naming an unknown knob.
TradeoffKnobs default_knobs(const Scene& scene, const std::vector<std::string>& names,
                            std::vector<std::string>& notes);

// The scene with a setting's knobs applied.
Scene apply_setting(const Scene& scene, const TradeoffSetting& setting);

// The references (rk45 at options.reference_tolerance, the smallest dt and the finest resolution
// of the sweep; one per physics setting), then every setting of the sweep. progress(done, total,
// label) is called before each run; `cancel`, when set, stops the sweep after the run in progress
// (report.cancelled).
using TradeoffProgress = FunctionRef<void(int done, int total, const std::string& label)>;
TradeoffReport run_tradeoff(const Scene& scene, const TradeoffOptions& options,
                            TradeoffProgress progress, const std::atomic<bool>* cancel = nullptr);

// Marks the points no other successful point beats in both wall time and centre error.
void mark_pareto_front(std::vector<TradeoffPoint>& points);

}  // namespace pbm
