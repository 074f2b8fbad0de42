// The "solver" and "camera" sections of a scene file (scenes/README.md).
#include "scene/scene_enum_names.h"
#include "scene/scene_sections.h"

namespace pbm {

namespace {

constexpr int kMaxRetriesLimit = 20;

constexpr auto kSolverFields = std::to_array<Field<SolverDef>>({
    value<&SolverDef::dt>(
        {.key = "dt", .unit = "s", .range = kPositive, .description = "Substep."}),
    choice<&SolverDef::integrator, kIntegratorKindNames>(
        {.key = "integrator", .description = "Time integrator."}),
    value<&SolverDef::tolerance>(
        {.key = "tolerance", .range = kPositive, .description = "rk45 local error tolerance."}),
    value<&SolverDef::adaptive>(
        {.key = "adaptive",
         .description = "implicit: choose each substep's length (dt down to dt / 1024) from a "
                        "local error estimate; rejected steps are counted."}),
    value<&SolverDef::adaptive_tolerance>(
        {.key = "adaptive_tolerance",
         .unit = "m",
         .range = kPositive,
         .description = "Largest local position error of an adaptive implicit substep."}),
    value<&SolverDef::shape_inertia_time>(
        {.key = "shape_inertia_time",
         .unit = "s",
         .range = kPositive,
         .default_note = "dt",
         .description = "Time scale tau of the shape parameters' inertia floor k_s tau^2; fixed, "
                        "dt can be refined without changing the model."}),
    value<&SolverDef::fps>({.key = "fps",
                            .unit = "1/s",
                            .range = kPositive,
                            .description = "Timeline frames per second."}),
    value<&SolverDef::duration>({.key = "duration",
                                 .unit = "s",
                                 .range = kPositive,
                                 .description = "Default length of a run."}),
    value<&SolverDef::contact_step_reduction>(
        {.key = "contact_step_reduction",
         .description = "Shrink dt while in contact (end of sec. 5.2.2)."}),
    value<&SolverDef::contact_dt_factor>({.key = "contact_dt_factor",
                                          .range = {.lo = 0, .hi = 1, .lo_open = true},
                                          .description = "dt multiplier while in contact."}),
    value<&SolverDef::max_retries>({.key = "max_retries",
                                    .range = {.lo = 0, .hi = kMaxRetriesLimit},
                                    .description = "Stability guard: step halvings per frame."}),
    // A bound below 1 would reject frames that merely conserve energy.
    value<&SolverDef::energy_growth_bound>(
        {.key = "energy_growth_bound",
         .range = {.lo = 1},
         .description = "Largest E_after / E_before accepted for one frame."}),
    value<&SolverDef::energy_tolerance>(
        {.key = "energy_tolerance",
         .range = kPositive,
         .description = "Run-level guard: growth of the total energy beyond the inputs' work, as "
                        "a fraction of the run's largest kinetic + elastic energy."}),
    value<&SolverDef::constraint_alpha>(
        {.key = "constraint_alpha",
         .unit = "1/s",
         .range = kNonNegative,
         .description = "Baumgarte alpha of (7.14): violations decay as e^(-alpha t) (7.16)."}),
    value<&SolverDef::constraint_beta>(
        {.key = "constraint_beta",
         .unit = "1/s",
         .range = kNonNegative,
         .default_note = "constraint_alpha",
         .description = "Baumgarte beta of (7.14); alpha = beta is critical damping."}),
    choice<&SolverDef::constraint_solver, kConstraintSolverKindNames>(
        {.key = "constraint_solver",
         .description = "Solve of N f_c + r = 0 (7.33): dense LU, or sparse LDL^T for loop-free "
                        "systems (loops fall back to dense)."}),
    value<&SolverDef::constraint_projection>(
        {.key = "constraint_projection",
         .description = "After collisions, restore each constraint's C and C-dot to their values "
                        "before them (position and velocity projection in the mass metric)."}),
    value<&SolverDef::body_collisions>(
        {.key = "body_collisions",
         .description = "Collisions between bodies (5.2.2); parts joined by a constraint never "
                        "collide."}),
    value<&SolverDef::self_collision>(
        {.key = "self_collision",
         .description = "A local body with itself (proximity, continuous detection, impact "
                        "zones)."}),
    value<&SolverDef::body_friction>({.key = "body_friction",
                                      .range = kUnitInterval,
                                      .description = "b_f of (5.13) between bodies."}),
    value<&SolverDef::body_elasticity>(
        {.key = "body_elasticity",
         .range = kNonNegative,
         .description = "a of (5.11) between bodies: the dents' elastic push on the global "
                        "surfaces; 0: inelastic impulses only."}),
    value<&SolverDef::collision_margin>({.key = "collision_margin",
                                         .unit = "m",
                                         .range = kPositive,
                                         .description = "Contact band between bodies."}),
});

}  // namespace

namespace {

void check_solver(const JsonNode& node, SolverDef& solver, const ReadContext&) {
  // rk45 adapts its step already; Euler and RK4 have no error estimate here.
  if (solver.adaptive && solver.integrator != IntegratorKind::implicit) {
    fail(node, "adaptive: only the implicit integrator takes an adaptive step (integrator is '" +
                   std::string(name_of(kIntegratorKindNames, solver.integrator)) + "')");
  }
}

}  // namespace

constexpr Section<SolverDef> kSolverSection{
    .name = "solver", .noun = "solver", .fields = kSolverFields, .check = check_solver};

namespace {

void check_camera(const JsonNode& node, CameraDef& camera, const ReadContext&) {
  if ((camera.target - camera.position).norm() < 1e-9) {
    fail(node, "position and target must differ");
  }
  if ((camera.target - camera.position).normalized().cross(camera.up).norm() < 1e-6) {
    fail(node, "up must not be parallel to the viewing direction");
  }
}

constexpr auto kCameraFields = std::to_array<Field<CameraDef>>({
    value<&CameraDef::position>(
        {.key = "position", .unit = "m", .description = "Where the camera is, world frame."}),
    value<&CameraDef::target>(
        {.key = "target", .unit = "m", .description = "The point it looks at, world frame."}),
    unit_vector<&CameraDef::up>(
        {.key = "up", .description = "Up on the picture; not along the viewing direction."}),
    value<&CameraDef::fov>({.key = "fov",
                            .unit = "degrees",
                            .range = {.lo = 0, .hi = 180, .lo_open = true, .hi_open = true},
                            .description = "Vertical field of view."}),
});

}  // namespace

// An empty camera takes every default: the studio's "add a scene camera".
constexpr Section<CameraDef> kCameraSection{.name = "camera",
                                            .noun = "camera",
                                            .fields = kCameraFields,
                                            .check = check_camera,
                                            .new_item = "{}"};

}  // namespace pbm
