// The names scene files use for each closed set of kinds in scene.h (scenes/README.md): the
// "kind" rows of the format's tables (scene_*_json.cpp) read and write them, so the reader, the
// writer and the schema check cannot disagree.
#pragma once

#include <array>
#include <string_view>
#include <utility>

#include "scene/scene.h"

namespace pbm {

template <typename Enum, std::size_t N>
using NameTable = std::array<std::pair<std::string_view, Enum>, N>;

inline constexpr NameTable<DeformLevel, 4> kDeformLevelNames{{{"rigid", DeformLevel::rigid},
                                                              {"global", DeformLevel::global},
                                                              {"local", DeformLevel::local},
                                                              {"auto", DeformLevel::automatic}}};
inline constexpr NameTable<DynamicsOrder, 2> kDynamicsOrderNames{
    {{"second", DynamicsOrder::second}, {"first", DynamicsOrder::first}}};
inline constexpr NameTable<ShapeKind, 3> kShapeKindNames{{{"superquadric", ShapeKind::superquadric},
                                                          {"taper_bend", ShapeKind::taper_bend},
                                                          {"general", ShapeKind::general}}};
inline constexpr NameTable<TessellationKind, 2> kTessellationKindNames{
    {{"quads", TessellationKind::quads}, {"triangles", TessellationKind::triangles}}};
inline constexpr NameTable<ContactQuadrature, 2> kContactQuadratureNames{
    {{"three-point", ContactQuadrature::three_point}, {"centroid", ContactQuadrature::centroid}}};
inline constexpr NameTable<IntegratorKind, 4> kIntegratorKindNames{
    {{"euler", IntegratorKind::euler},
     {"rk4", IntegratorKind::rk4},
     {"rk45", IntegratorKind::rk45},
     {"implicit", IntegratorKind::implicit}}};
inline constexpr NameTable<ObstacleKind, 3> kObstacleKindNames{
    {{"plane", ObstacleKind::plane}, {"box", ObstacleKind::box}, {"mesh", ObstacleKind::mesh}}};
inline constexpr NameTable<ForceFieldKind, 2> kForceFieldKindNames{
    {{"acceleration", ForceFieldKind::acceleration},
     {"force_per_node", ForceFieldKind::force_per_node}}};
inline constexpr NameTable<Interpolation, 3> kInterpolationNames{{{"linear", Interpolation::linear},
                                                                  {"smooth", Interpolation::smooth},
                                                                  {"step", Interpolation::step}}};
inline constexpr NameTable<ConstraintKind, 2> kConstraintKindNames{
    {{"point", ConstraintKind::point}, {"hinge", ConstraintKind::hinge}}};
inline constexpr NameTable<ConstraintSolverKind, 2> kConstraintSolverKindNames{
    {{"dense", ConstraintSolverKind::dense}, {"sparse", ConstraintSolverKind::sparse}}};
inline constexpr NameTable<JointKind, 6> kJointKindNames{{{"revolute", JointKind::revolute},
                                                          {"prismatic", JointKind::prismatic},
                                                          {"spherical", JointKind::spherical},
                                                          {"universal", JointKind::universal},
                                                          {"fixed", JointKind::fixed},
                                                          {"free", JointKind::free}}};
inline constexpr NameTable<ControllerKind, 3> kControllerKindNames{
    {{"mrac", ControllerKind::mrac},
     {"pd", ControllerKind::pd},
     {"stable_pd", ControllerKind::stable_pd}}};
inline constexpr NameTable<SegmentShapeKind, 4> kSegmentShapeKindNames{
    {{"box", SegmentShapeKind::box},
     {"sphere", SegmentShapeKind::sphere},
     {"cylinder", SegmentShapeKind::cylinder},
     {"capsule", SegmentShapeKind::capsule}}};
inline constexpr NameTable<ImpulseFrame, 2> kImpulseFrameNames{
    {{"world", ImpulseFrame::world}, {"site", ImpulseFrame::site}}};
inline constexpr NameTable<LiquidAdvection, 3> kLiquidAdvectionNames{
    {{"book", LiquidAdvection::book},
     {"semi_lagrangian", LiquidAdvection::semi_lagrangian},
     {"flip", LiquidAdvection::flip}}};
inline constexpr NameTable<PressureSolver, 3> kPressureSolverNames{
    {{"relaxation", PressureSolver::relaxation},
     {"mic_pcg", PressureSolver::mic_pcg},
     {"mgpcg", PressureSolver::mgpcg}}};
inline constexpr NameTable<SurfaceMethod, 3> kSurfaceMethodNames{
    {{"markers", SurfaceMethod::markers},
     {"height_field", SurfaceMethod::height_field},
     {"chains", SurfaceMethod::chains}}};
inline constexpr NameTable<LiquidDisplay, 3> kLiquidDisplayNames{
    {{"surface", LiquidDisplay::surface},
     {"markers", LiquidDisplay::markers},
     {"both", LiquidDisplay::both}}};
inline constexpr NameTable<LiquidSection, 3> kLiquidSectionNames{
    {{"none", LiquidSection::none},
     {"pressure", LiquidSection::pressure},
     {"speed", LiquidSection::speed}}};
inline constexpr NameTable<SectionAxis, 3> kSectionAxisNames{
    {{"x", SectionAxis::x}, {"y", SectionAxis::y}, {"z", SectionAxis::z}}};
inline constexpr NameTable<LiquidCoupling, 2> kLiquidCouplingNames{
    {{"one_way", LiquidCoupling::one_way}, {"two_way", LiquidCoupling::two_way}}};
inline constexpr NameTable<WallKind, 2> kWallKindNames{
    {{"free_slip", WallKind::free_slip}, {"no_slip", WallKind::no_slip}}};

// The scene file's name of a kind ("" if the table lacks it): what messages, CSV columns and
// labels print, so they use the words a scene file does.
template <typename Enum, std::size_t N>
constexpr const char* name_of(const NameTable<Enum, N>& table, Enum value) {
  for (const auto& [name, kind] : table) {
    if (kind == value) return name.data();
  }
  return "";
}

}  // namespace pbm
