// The "liquids[i]" section of a scene file (scenes/README.md): the grid of ch. 16 over a box of
// the world, where the liquid starts, its walls, sources and sinks, and the solver's knobs.
#include <array>
#include <string>

#include "liquid/liquid_model.h"
#include "scene/scene_enum_names.h"
#include "scene/scene_sections.h"

namespace pbm {

namespace {

// Cells along one axis: far above the book's grids (50 x 15 x 40), with kMaxLiquidCells bounding
// the whole grid.
constexpr Real kMaxCellsPerAxis = 4096;
constexpr Real kMaxLiquidBoxes = 256;  // fluid regions, solid boxes
constexpr Real kMaxLiquidPorts = 64;   // inflows, outflows

// The grid's cells per axis: three integers (a Vector3i, which the generic rows do not read).
constexpr Field<LiquidDef> resolution_row(FieldFormat format) {
  format.type = ValueType::counts;
  format.size = 3;
  return {format,
          [](const FieldFormat& f, const JsonNode& node, LiquidDef& def, const ReadContext&) {
            if (!node.value->is_array() || node.value->size() != 3) {
              fail(node, "must be an array of 3 integers");
            }
            for (int k = 0; k < 3; ++k) {
              const JsonNode entry = element(node, static_cast<std::size_t>(k));
              def.resolution[k] = static_cast<int>(check_range(f, entry, read_int(entry)));
            }
          },
          [](const FieldFormat& f, const LiquidDef& def, OrderedJson& object) {
            object[f.key] = {def.resolution.x(), def.resolution.y(), def.resolution.z()};
          }};
}

constexpr auto kLiquidBoxFields = std::to_array<Field<LiquidBoxDef>>({
    value<&LiquidBoxDef::min>(
        {.key = "min", .unit = "m", .required = true, .description = "The lowest corner."}),
    value<&LiquidBoxDef::max>({.key = "max",
                               .unit = "m",
                               .required = true,
                               .description = "The highest corner, above min on every axis."}),
});

void check_box(const JsonNode& node, LiquidBoxDef& box, const ReadContext&) {
  for (int a = 0; a < 3; ++a) {
    if (!(box.max[a] > box.min[a])) {
      fail(element(require_child(node, "max"), static_cast<std::size_t>(a)),
           "must be above min[" + std::to_string(a) + "] (" + format_real(box.min[a]) + ")");
    }
  }
}

constexpr auto kFluidRegionFields = std::to_array<Field<FluidRegionDef>>({
    object<&FluidRegionDef::box, kLiquidBoxSection>(
        {.key = "box",
         .required = true,
         .section = "liquid_box",
         .description = "The cells whose centres it holds start full of liquid."}),
    value<&FluidRegionDef::velocity>(
        {.key = "velocity", .unit = "m/s", .description = "The liquid's initial velocity."}),
});

constexpr auto kInflowFields = std::to_array<Field<InflowDef>>({
    object<&InflowDef::box, kLiquidBoxSection>(
        {.key = "box",
         .required = true,
         .section = "liquid_box",
         .description = "Its cells (those whose centres it holds): Inflow cells of 16.2.2."}),
    value<&InflowDef::velocity>(
        {.key = "velocity", .unit = "m/s", .description = "The velocity it imposes."}),
    value<&InflowDef::markers_per_second>(
        {.key = "markers_per_second",
         .unit = "1/s",
         .range = kNonNegative,
         .description = "Markers released per second (the book's jet: 500); 0: as many as keep "
                        "the released liquid at the marker density."}),
});

constexpr auto kSurfaceWaveFields = std::to_array<Field<SurfaceWaveDef>>({
    value<&SurfaceWaveDef::amplitude>(
        {.key = "amplitude",
         .unit = "m",
         .range = kPositive,
         .description = "a: the wave's height above the mean when the forcing ends."}),
    value<&SurfaceWaveDef::wavelength>({.key = "wavelength",
                                        .unit = "m",
                                        .range = kPositive,
                                        .description = "2L, crest to crest; C = pi / L (16.19)."}),
    value<&SurfaceWaveDef::direction>(
        {.key = "direction",
         .description = "The way it travels (its part across gravity, in a 2D liquid's plane)."}),
    value<&SurfaceWaveDef::depth>(
        {.key = "depth",
         .unit = "m",
         .range = kNonNegative,
         .description = "D, the mean depth its speed follows from; 0: the liquid's at the start."}),
    value<&SurfaceWaveDef::start>(
        {.key = "start", .unit = "s", .range = kNonNegative, .description = "When it starts."}),
    value<&SurfaceWaveDef::duration>(
        {.key = "duration",
         .unit = "s",
         .range = kPositive,
         .description = "T: how long the pressure forces the wave, growing it to its amplitude "
                        "(a shorter T: a stronger pressure)."}),
});

constexpr auto kLiquidFields = std::to_array<Field<LiquidDef>>({
    value<&LiquidDef::name>({.key = "name", .default_note = "liquid<i>"}),
    object<&LiquidDef::domain, kLiquidBoxSection>(
        {.key = "domain",
         .section = "liquid_box",
         .default_note = "[0, 0, 0] to [1, 1, 1]",
         .description = "The grid's extent; its faces are walls unless an inflow or outflow "
                        "opens them."}),
    resolution_row({.key = "resolution",
                    .range = {.lo = 1},
                    .limit = kMaxCellsPerAxis,
                    .description = "Cells per axis, at most 16,777,216 (256^3) in all; 1 on one "
                                   "axis: a 2D liquid one cell thick."}),
    list<&LiquidDef::fluid, kFluidRegionSection>({.key = "fluid",
                                                  .limit = kMaxLiquidBoxes,
                                                  .section = "fluid_region",
                                                  .description = "Where the liquid starts."}),
    list<&LiquidDef::solids, kLiquidBoxSection>({.key = "solids",
                                                 .limit = kMaxLiquidBoxes,
                                                 .section = "liquid_box",
                                                 .description = "Boxes of Solid cells."}),
    list<&LiquidDef::inflows, kInflowSection>({.key = "inflows",
                                               .limit = kMaxLiquidPorts,
                                               .section = "inflow",
                                               .description = "Where liquid enters (16.2.2)."}),
    list<&LiquidDef::outflows, kLiquidBoxSection>(
        {.key = "outflows",
         .limit = kMaxLiquidPorts,
         .section = "liquid_box",
         .description = "Cells the liquid leaves by at its own velocity (16.2.2)."}),
    value<&LiquidDef::density>({.key = "density",
                                .unit = "kg/m^3",
                                .range = kPositive,
                                .description = "rho: the pressure is rho times the kinematic "
                                               "pressure the solve finds (16.1)."}),
    value<&LiquidDef::viscosity>({.key = "viscosity",
                                  .unit = "m^2/s",
                                  .range = kNonNegative,
                                  .description = "Kinematic viscosity nu of (16.1) (water: "
                                                 "1e-6)."}),
    value<&LiquidDef::drag>({.key = "drag",
                             .range = {.lo = 0, .hi = 100},
                             .description = "C_d of the drag on bodies in the liquid: -1/2 rho "
                                            "C_d A |v_rel| v_rel over their faces moving into it "
                                            "(16.16); 0: buoyancy alone."}),
    choice<&LiquidDef::walls, kWallKindNames>(
        {.key = "walls",
         .description = "The domain's and the solids' walls: free_slip (a plane of symmetry) or "
                        "no_slip (tangential velocity zero), 16.2.2."}),
    choice<&LiquidDef::coupling, kLiquidCouplingNames>(
        {.key = "coupling",
         .description = "two_way: the scene's bodies and obstacles are Solid cells moving with "
                        "them, displacing the liquid (markers only: a height field is coupled one "
                        "way); one_way: the book's 16.4, bodies feel the liquid but do not move "
                        "it."}),
    value<&LiquidDef::surface_pressure>(
        {.key = "surface_pressure",
         .unit = "Pa",
         .description = "Applied on the free surface above the atmosphere's (16.6.2)."}),
    list<&LiquidDef::surface_waves, kSurfaceWaveSection>(
        {.key = "surface_waves",
         .limit = kMaxLiquidPorts,
         .section = "surface_wave",
         .description = "Travelling waves forced by a pressure history on the free surface, p "
                        "= B cos(C s - omega t) (16.17)-(16.19)."}),
    choice<&LiquidDef::advection, kLiquidAdvectionNames>(
        {.key = "advection",
         .description = "book: the explicit differences of (16.2); semi_lagrangian: a "
                        "backtrace, unconditionally stable; flip: the markers carry the velocity "
                        "(PIC/FLIP, markers only)."}),
    value<&LiquidDef::flip_ratio>(
        {.key = "flip_ratio",
         .range = kUnitInterval,
         .description = "With advection flip: the FLIP share of the markers' velocity update (1: "
                        "FLIP, no dissipation; 0: PIC, smooth)."}),
    choice<&LiquidDef::solver, kPressureSolverNames>(
        {.key = "solver",
         .description = "The pressure solve: the book's relaxation (16.5)-(16.9), or conjugate "
                        "gradients with MIC(0) or a multigrid preconditioner."}),
    choice<&LiquidDef::surface, kSurfaceMethodNames>(
        {.key = "surface",
         .description = "markers (16.3.1), a height field (16.3.3) for surfaces that do not "
                        "overturn, or free-surface marker chains (16.3.2, 2D only)."}),
    choice<&LiquidDef::display, kLiquidDisplayNames>(
        {.key = "display",
         .description = "What is drawn of a marker liquid: its surface (a translucent mesh of "
                        "a level set of the markers), the markers as points, or both."}),
    choice<&LiquidDef::section, kLiquidSectionNames>(
        {.key = "section",
         .description = "A cross-section of the grid drawn in false colour with a colour bar: "
                        "none, the pressure [Pa] or the speed [m/s] at the cells' centres."}),
    choice<&LiquidDef::section_axis, kSectionAxisNames>(
        {.key = "section_axis", .description = "The axis the cross-section is across."}),
    value<&LiquidDef::section_position>(
        {.key = "section_position",
         .range = kUnitInterval,
         .description = "Where the cross-section is: a fraction of the domain along its axis."}),
    value<&LiquidDef::cfl>({.key = "cfl",
                            .range = {.lo = 0, .hi = 1, .lo_open = true},
                            .description = "The CFL number (16.3) every substep keeps to: the "
                                           "substeps per frame follow from it."}),
    value<&LiquidDef::relaxation>({.key = "relaxation",
                                   .range = {.lo = 1, .hi = 2, .hi_open = true},
                                   .description = "beta_0 of (16.7), the relaxation's "
                                                  "over-relaxation."}),
    value<&LiquidDef::tolerance>({.key = "tolerance",
                                  .unit = "1/s",
                                  .range = kPositive,
                                  .description = "epsilon: every Full cell's divergence below "
                                                 "it after a solve (book: 1e-4)."}),
    value<&LiquidDef::relative_tolerance>(
        {.key = "relative_tolerance",
         .range = {.lo = 0, .hi = 1, .hi_open = true},
         .description = "When > 0, the solve stops once its residual is this fraction of the "
                        "divergence it started from (instead of tolerance)."}),
    value<&LiquidDef::max_iterations>({.key = "max_iterations",
                                       .range = {.lo = 1},
                                       .limit = 100000,
                                       .description = "Of one pressure solve."}),
    value<&LiquidDef::max_substeps>(
        {.key = "max_substeps",
         .range = {.lo = 1},
         .limit = 1000000,
         .description = "Substeps the liquid may take in one frame; a flow that needs more is "
                        "unstable and stops the run with a message."}),
    value<&LiquidDef::markers_per_axis>(
        {.key = "markers_per_axis",
         .range = {.lo = 1},
         .limit = 8,
         .description = "Markers per cell along each axis of the grid's plane or space."}),
    value<&LiquidDef::ghost_fluid>(
        {.key = "ghost_fluid",
         .description = "The surface's pressure placed where the surface is inside its cell "
                        "(exact for still water); false: at the cell's centre, as the book."}),
    value<&LiquidDef::volume_correction>(
        {.key = "volume_correction",
         .range = kUnitInterval,
         .description = "Fraction of the markers' excess density the solve pushes apart per "
                        "substep, or of the chains' drift from their starting area it restores "
                        "(0: div u = 0 exactly, the book's)."}),
    value<&LiquidDef::spray_speed>(
        {.key = "spray_speed",
         .unit = "m/s",
         .range = kNonNegative,
         .description = "Spray leaves Surface cells whose liquid rises faster than this (markers "
                        "only); 0: no spray or foam."}),
    value<&LiquidDef::spray_rate>({.key = "spray_rate",
                                   .unit = "1/s",
                                   .range = kNonNegative,
                                   .limit = 1e6,
                                   .description = "Spray particles per rising cell per second."}),
    value<&LiquidDef::spray_drag>(
        {.key = "spray_drag",
         .unit = "1/m",
         .range = kNonNegative,
         .limit = 1e3,
         .description = "k of the spray's air drag a = g - k |v| v: terminal speed sqrt(g / k)."}),
    value<&LiquidDef::foam_lifetime>({.key = "foam_lifetime",
                                      .unit = "s",
                                      .range = kNonNegative,
                                      .limit = 1e4,
                                      .description = "How long foam rides the surface."}),
    value<&LiquidDef::max_spray>({.key = "max_spray",
                                  .range = {.lo = 0},
                                  .limit = 10000000,
                                  .description = "The most spray particles, and of foam."}),
});

// Where a box of the liquid lies wholly inside its domain.
bool inside(const LiquidBoxDef& box, const LiquidBoxDef& domain) {
  return (box.min.array() >= domain.min.array()).all() &&
         (box.max.array() <= domain.max.array()).all();
}

void check_boxes_inside(const JsonNode& node, std::string_view key, const LiquidDef& liquid,
                        std::size_t count,
                        const LiquidBoxDef& (*box_of)(const LiquidDef&, std::size_t)) {
  for (std::size_t k = 0; k < count; ++k) {
    if (inside(box_of(liquid, k), liquid.domain)) continue;
    JsonNode item = element(require_child(node, key), k);
    if (const std::optional<JsonNode> box = find_child(item, "box")) item = *box;
    fail(item, "lies outside the liquid's domain");
  }
}

void check_liquid(const JsonNode& node, LiquidDef& liquid, const ReadContext& context) {
  const Eigen::Vector3i& n = liquid.resolution;
  const long cells = static_cast<long>(n.x()) * n.y() * n.z();
  if (cells > kMaxLiquidCells) {
    fail(require_child(node, "resolution"), "has " + std::to_string(cells) +
                                                " cells; a liquid may have at most " +
                                                std::to_string(kMaxLiquidCells) + " (256^3)");
  }
  if ((n.array() == 1).count() > 1) {
    fail(require_child(node, "resolution"), "may have 1 cell on one axis only (a 2D liquid)");
  }
  check_boxes_inside(
      node, "fluid", liquid, liquid.fluid.size(),
      [](const LiquidDef& l, std::size_t k) -> const LiquidBoxDef& { return l.fluid[k].box; });
  check_boxes_inside(
      node, "solids", liquid, liquid.solids.size(),
      [](const LiquidDef& l, std::size_t k) -> const LiquidBoxDef& { return l.solids[k]; });
  check_boxes_inside(
      node, "inflows", liquid, liquid.inflows.size(),
      [](const LiquidDef& l, std::size_t k) -> const LiquidBoxDef& { return l.inflows[k].box; });
  check_boxes_inside(
      node, "outflows", liquid, liquid.outflows.size(),
      [](const LiquidDef& l, std::size_t k) -> const LiquidBoxDef& { return l.outflows[k]; });
  if (earlier_with(context.scene.liquids, context.index, &LiquidDef::name, liquid.name) >= 0) {
    const std::optional<JsonNode> name = find_child(node, "name");
    fail(name ? *name : node, "'" + liquid.name + "' names an earlier liquid");
  }
}

}  // namespace

constexpr Section<LiquidBoxDef> kLiquidBoxSection{
    .name = "liquid_box", .noun = "box", .fields = kLiquidBoxFields, .check = check_box};

constexpr Section<FluidRegionDef> kFluidRegionSection{
    .name = "fluid_region", .noun = "fluid region", .fields = kFluidRegionFields};

constexpr Section<InflowDef> kInflowSection{
    .name = "inflow", .noun = "inflow", .fields = kInflowFields};

constexpr Section<SurfaceWaveDef> kSurfaceWaveSection{
    .name = "surface_wave", .noun = "surface wave", .fields = kSurfaceWaveFields};

// A tank 1 m wide with water 0.4 m deep at rest, beside the origin, for the studio's "add".
constexpr Section<LiquidDef> kLiquidSection{
    .name = "liquid",
    .noun = "liquid",
    .fields = kLiquidFields,
    .init =
        [](LiquidDef& liquid, const ReadContext& context) {
          liquid.name = "liquid" + std::to_string(context.index);
        },
    .check = check_liquid,
    .new_item = R"({"domain": {"min": [-0.5, -0.5, 0], "max": [0.5, 0.5, 1]},
                    "resolution": [16, 16, 16],
                    "fluid": [{"box": {"min": [-0.5, -0.5, 0], "max": [0.5, 0.5, 0.4]}}]})"};

}  // namespace pbm
