#include "deform/body_model.h"

#include <cmath>
#include <map>
#include <numbers>

#include "core/error.h"
#include "deform/body_dynamics.h"
#include "deform/reference_shape.h"

namespace pbm {
namespace {

// Where obstacles push a local body (collide/rigid_contact.h): material points in each surface
// triangle (three: barycentric 2/3, 1/6, 1/6, Strang-Fix's degree-2 rule; or the centroid), each
// with its share of the triangle's area on the initial shape times the book's stiffness per area,
// sum K_ii / area. Nodes alone would carry a K_ii each: densest where the (u, v) grid crowds (the
// poles), and few enough in a contact patch that a resting ball's depth would change as one enters
// or leaves. The points lie on the exact surface s(u, v): on the flat triangles, the equator's
// larger chords would sit deeper than the poles' and a ball would roll toward its deepest
// orientation.
void build_contact_samples(BodyModel& body, ContactQuadrature rule, Real contact_stiffness) {
  const Tessellation& t = body.tessellation;
  const int per_triangle = contact_samples_per_triangle(rule);
  body.samples_per_triangle = per_triangle;
  body.contact_samples.clear();
  body.contact_samples.reserve(per_triangle * t.triangles.size());
  body.contact_triangle_reach.clear();
  body.sample_grid_u.clear();
  body.sample_grid_v.clear();
  std::map<Real, int> u_index, v_index;  // the samples' distinct latitudes and longitudes
  Real total_area = 0, gap = 0;
  for (const std::array<int, 3>& tri : t.triangles) {
    const Vec3& p0 = body.s_fixed[tri[0]];
    const Real area = 0.5 * (body.s_fixed[tri[1]] - p0).cross(body.s_fixed[tri[2]] - p0).norm();
    total_area += area;
    Real reach = 0;
    // v of a pole is arbitrary: the point's v comes from the triangle's other nodes, unwrapped
    // across the seam.
    Real v_ref = 0;
    for (int k = 0; k < 3; ++k) {
      if (tri[k] != t.south_pole && tri[k] != t.north_pole) v_ref = t.uv[tri[k]].y();
    }
    for (int k = 0; k < per_triangle; ++k) {
      ContactSample sample;
      sample.nodes = tri;
      if (per_triangle == 1) {
        sample.weights.setConstant(1.0 / 3.0);
      } else {
        sample.weights.setConstant(1.0 / 6.0);
        sample.weights[k] = 2.0 / 3.0;
      }
      sample.stiffness = area / per_triangle;
      Real u = 0, v = 0, v_weight = 0;
      Vec3 blended = Vec3::Zero();
      for (int m = 0; m < 3; ++m) {
        const Vec2& uv = t.uv[tri[m]];
        u += sample.weights[m] * uv.x();
        blended += sample.weights[m] * body.s_fixed[tri[m]];
        if (tri[m] == t.south_pole || tri[m] == t.north_pole) continue;
        const Real unwrapped = v_ref + std::remainder(uv.y() - v_ref, 2 * std::numbers::pi);
        v += sample.weights[m] * unwrapped;
        v_weight += sample.weights[m];
      }
      v = std::remainder(v / v_weight, 2 * std::numbers::pi);
      sample.angles = superquadric_angles(u, v);
      auto [u_it, u_new] = u_index.emplace(u, static_cast<int>(body.sample_grid_u.size()));
      if (u_new) body.sample_grid_u.push_back(superquadric_angles(u, 0.0));
      auto [v_it, v_new] = v_index.emplace(v, static_cast<int>(body.sample_grid_v.size()));
      if (v_new) body.sample_grid_v.push_back(superquadric_angles(0.0, v));
      sample.grid = {u_it->second, v_it->second};
      Vec3 exact;
      evaluate_reference_shape(body.shape, body.q_s_fixed, sample.angles, 1.0, exact, nullptr);
      gap = std::max(gap, (exact - blended).norm());
      for (int m = 0; m < 3; ++m) reach = std::max(reach, (exact - body.s_fixed[tri[m]]).norm());
      body.contact_samples.push_back(sample);
    }
    body.contact_triangle_reach.push_back(reach);
  }
  body.book_contact_stiffness = membrane_stiffness_diagonal(t, body.stiffness).sum() / total_area;
  const Real per_area = contact_stiffness > 0 ? contact_stiffness : body.book_contact_stiffness;
  for (ContactSample& sample : body.contact_samples) sample.stiffness *= per_area;
  body.contact_sample_gap = gap;
}

// Lumped node masses (sec. 6.1). The book gives one mass per node; a total mass or an areal
// density is spread by each node's share of the initial surface, a third of the areas of its
// triangles, so that refining the mesh approaches one continuum (docs/architecture.md, "Knobs
// that converge") instead of adding mass.
void distribute_mass(const MaterialDef& material, const std::string& file, const std::string& path,
                     BodyModel& body) {
  const int given = (material.nodal_mass > 0) + (material.mass > 0) + (material.density > 0);
  if (given != 1) {
    throw Error(file, path + ".material", "give exactly one of mass, density and nodal_mass > 0");
  }
  const int n = body.tessellation.node_count();
  VecX area = VecX::Zero(n);
  for (const std::array<int, 3>& tri : body.tessellation.triangles) {
    const Vec3& p0 = body.s_fixed[tri[0]];
    const Real a = 0.5 * (body.s_fixed[tri[1]] - p0).cross(body.s_fixed[tri[2]] - p0).norm() / 3.0;
    for (int k = 0; k < 3; ++k) area[tri[k]] += a;
  }
  body.surface_area = area.sum();
  if (material.nodal_mass > 0) {
    body.node_mass = VecX::Constant(n, material.nodal_mass);
    body.mass = material.nodal_mass * n;
  } else {
    body.node_mass = material.density > 0 ? VecX(material.density * area)
                                          : VecX((material.mass / body.surface_area) * area);
    body.mass = body.node_mass.sum();
  }
  if (!(body.node_mass.minCoeff() > 0) || !std::isfinite(body.mass)) {
    throw Error(file, path + ".material",
                "mass, density or nodal_mass must give every node a finite mass > 0");
  }
}

}  // namespace

BodyModel build_body_model(const BodyDef& def, Real tau, const std::string& file,
                           const std::string& path) {
  BodyModel body;
  body.name = def.name;
  body.level = def.level;
  body.order = def.order;
  body.shape = def.shape;
  body.n_shape = shape_parameter_count(def.shape);
  body.n_s = def.level == DeformLevel::rigid ? 0 : body.n_shape;
  body.has_local = def.level == DeformLevel::local || def.level == DeformLevel::automatic;
  body.auto_level = def.level == DeformLevel::automatic;
  body.tessellation = tessellate(def.tessellation);
  const int n = body.tessellation.node_count();
  body.damping = def.material.damping;
  if (def.order == DynamicsOrder::first && !(body.damping > 0)) {
    throw Error(file, path + ".material.damping",
                "must be > 0 for a first-order body (3.51 divides by D)");
  }
  body.w0 = def.material.w0;
  body.w1 = def.material.w1;
  body.color = def.material.color;
  body.roughness = def.material.roughness;
  body.q_s_fixed = def.q_s.size() ? def.q_s : default_shape_parameters(def.shape);
  body.q_s0 = def.q_s0.size() ? def.q_s0 : body.q_s_fixed;
  body.k_s = def.k_s.size() ? def.k_s : VecX::Zero(body.n_shape);
  if (body.has_local) {
    body.stiffness = build_membrane_stiffness(body.tessellation, body.w0, body.w1);
  }
  // Reference shape at the initial parameters: the shape of a rigid body.
  body.s_fixed.resize(n);
  body.node_angles.resize(n);
  {
    std::map<Real, int> u_index, v_index;
    body.node_grid.resize(n);
    for (int i = 0; i < n; ++i) {
      const Vec2& uv = body.tessellation.uv[i];
      auto [u_it, u_new] = u_index.emplace(uv.x(), static_cast<int>(body.grid_u.size()));
      if (u_new) body.grid_u.push_back(superquadric_angles(uv.x(), 0.0));
      auto [v_it, v_new] = v_index.emplace(uv.y(), static_cast<int>(body.grid_v.size()));
      if (v_new) body.grid_v.push_back(superquadric_angles(0.0, uv.y()));
      body.node_grid[i] = {u_it->second, v_it->second};
    }
  }
  for (int i = 0; i < n; ++i) {
    const Vec2& uv = body.tessellation.uv[i];
    body.node_angles[i] = superquadric_angles(uv.x(), uv.y());
    evaluate_reference_shape(def.shape, body.q_s_fixed, body.node_angles[i], 1.0, body.s_fixed[i],
                             nullptr);
  }
  distribute_mass(def.material, file, path, body);
  body.contact_from_material = def.material.contact_stiffness > 0;
  if (body.has_local) {
    build_contact_samples(body, def.tessellation.contact, def.material.contact_stiffness);
  }
  // Inertia of the gauge direction n (deform/body_dynamics.h): omega = sqrt(n^T K_ss n / eta)
  // at most 1 / (4 tau), and at least 1% of the mass times a0^2 so it is never negligible.
  // Parameters whose mass vanishes at some shapes (a bend's location and range weigh nothing
  // while its amount is 0) get the floor eta_i = k_i tau^2, so omega_i tau <= 1 everywhere. tau
  // is solver.shape_inertia_time, by default solver.dt; the substep is kept below the limit this
  // sets (deform/stability_limit.h), so a fixed tau leaves dt free to be refined.
  body.parameter_inertia_floor = body.k_s.head(body.n_s) * tau * tau;
  if (body.n_s >= 4) {
    const VecX n_gauge = gauge_direction(body.q_s_fixed);
    const Real k_gauge = n_gauge.dot(body.k_s.cwiseProduct(n_gauge));
    body.parameter_inertia = std::max(16.0 * k_gauge * tau * tau,
                                      1e-2 * body.mass * body.q_s_fixed[0] * body.q_s_fixed[0]);
  }
  if (body.level != DeformLevel::rigid) body.s_fixed.clear();
  body.layout.n_s = body.n_s;
  body.layout.n_d = body.has_local ? 3 * n : 0;
  body.q_size = body.layout.q_size();
  body.v_size = body.layout.v_size();
  body.stability = explicit_stability_limit(body);
  return body;
}

}  // namespace pbm
