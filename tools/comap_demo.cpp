// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// comap demo: the whole pipeline on a pair with known ground truth that the project may
// redistribute. The source is data/meshes/homer.off of the Debian package libcgal-demo (extracted
// at run time); the target is a second pose of it, made by a near-isometric deformation (both
// arms rotated about the shoulders and the head turned, with smooth skinning weights) and an
// independent isotropic remeshing, so that the ground truth is known from the construction.
// Without libcgal-demo, a generated bumpy capsule and a bent copy of it are used.

#include "comap_commands.h"
#include "comap_report.h"
#include "comap_settings.h"
#include "comap_svg.h"
#include "comap_transfer.h"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Polygon_mesh_processing/locate.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>

namespace comap {

namespace {

const char* const cgal_demo_data = "/usr/share/doc/libcgal-demo/data.tar.gz";

double smoothstep(double t)
{
  t = std::min(1.0, std::max(0.0, t));
  return t * t * (3 - 2 * t);
}

/// Homer (data/meshes/homer.off: y up, height 1, arms stretched sideways along x at shoulder
/// height y = 0.07, the body within |x| < 0.15): the left arm is lowered by 30 degrees and the
/// right arm raised by 15 degrees about the shoulder joints (rotation about the z axis, weight
/// rising smoothly from |x| = 0.13 to 0.26), and the head is turned by 20 degrees about the
/// vertical axis (weight rising from y = 0.14 to 0.34). Edge lengths change by 1.6% on average
/// (by more than 10% on 4% of the edges, in the bent parts of the arms).
Point pose_homer(const Point& p)
{
  double x = p.x(), y = p.y(), z = p.z();
  // Arms (not the feet, which also reach |x| > 0.14, at y < -0.4).
  const double arm = smoothstep((std::abs(x) - 0.13) / 0.13) * smoothstep((y + 0.08) / 0.06);
  if(arm > 0)
  {
    const double jx = x < 0 ? -0.15 : 0.15, jy = 0.07;
    const double angle = arm * (x < 0 ? 30.0 : 15.0) * CGAL_PI / 180;  // counter-clockwise: left down, right up
    const double dx = x - jx, dy = y - jy, c = std::cos(angle), s = std::sin(angle);
    x = jx + c * dx - s * dy;
    y = jy + s * dx + c * dy;
  }
  const double head = smoothstep((y - 0.14) / 0.20) * (1.0 - smoothstep((std::abs(p.x()) - 0.12) / 0.02));
  if(head > 0)
  {
    const double angle = head * 20.0 * CGAL_PI / 180, c = std::cos(angle), s = std::sin(angle);
    const double cz = -0.02;
    const double dx = x, dz = z - cz;
    x = c * dx + s * dz;
    z = cz - s * dx + c * dz;
  }
  return Point(x, y, z);
}

/// A capsule of radius 1 and body length 4 along z, with bumps that break its symmetries
/// (the fallback shape when libcgal-demo is missing).
Mesh bumpy_capsule()
{
  const int nu = 40, n_cap = 10, n_body = 30;
  const double length = 4.0;
  Mesh m;
  std::vector<Mesh::Vertex_index> ring_vertices;
  auto bump = [](double a, double z) {
    return 1.0 + 0.12 * std::sin(3 * z + 0.5) * std::cos(2 * a + 0.3 * z) + 0.06 * std::cos(5 * a - 1.1 * z);
  };
  // Profile: rings from the south cap through the body to the north cap (poles separate).
  std::vector<std::pair<double, double> > profile;  // (radius, z)
  for(int i = 1; i <= n_cap; ++i)
  {
    const double t = -CGAL_PI / 2 + (CGAL_PI / 2) * i / n_cap;
    profile.emplace_back(std::cos(t), -length / 2 + std::sin(t));
  }
  for(int i = 1; i < n_body; ++i) profile.emplace_back(1.0, -length / 2 + length * i / n_body);
  for(int i = 0; i < n_cap; ++i)
  {
    const double t = (CGAL_PI / 2) * i / n_cap;
    profile.emplace_back(std::cos(t), length / 2 + std::sin(t));
  }
  const Mesh::Vertex_index south = m.add_vertex(Point(0, 0, -length / 2 - 1));
  for(std::size_t r = 0; r < profile.size(); ++r)
    for(int i = 0; i < nu; ++i)
    {
      const double a = 2 * CGAL_PI * (i + 0.5 * (r % 2)) / nu, z = profile[r].second;
      const double rad = profile[r].first * bump(a, z);
      ring_vertices.push_back(m.add_vertex(Point(rad * std::cos(a), rad * std::sin(a), z)));
    }
  const Mesh::Vertex_index north = m.add_vertex(Point(0, 0, length / 2 + 1));
  auto v = [&](std::size_t r, int i) { return ring_vertices[r * nu + ((i % nu) + nu) % nu]; };
  for(int i = 0; i < nu; ++i) m.add_face(south, v(0, i + 1), v(0, i));
  for(std::size_t r = 0; r + 1 < profile.size(); ++r)
    for(int i = 0; i < nu; ++i)
    {
      // Odd rings are rotated by half a step: vertex (r + 1, i) lies between (r, i) and (r, i + 1)
      // when r is even, and (r, i) between (r + 1, i) and (r + 1, i + 1) when r is odd.
      if(r % 2 == 0)
      {
        m.add_face(v(r, i), v(r, i + 1), v(r + 1, i));
        m.add_face(v(r, i + 1), v(r + 1, i + 1), v(r + 1, i));
      }
      else
      {
        m.add_face(v(r, i), v(r + 1, i + 1), v(r + 1, i));
        m.add_face(v(r, i), v(r, i + 1), v(r + 1, i + 1));
      }
    }
  const std::size_t last = profile.size() - 1;
  for(int i = 0; i < nu; ++i) m.add_face(north, v(last, i), v(last, i + 1));
  return m;
}

/// Bends the capsule by 60 degrees in the x-z plane (radius of curvature 4 / (pi / 3)).
Point bend_capsule(const Point& p)
{
  const double angle = CGAL_PI / 3, length = 4.0, radius = length / angle;
  const double t = std::min(std::max(p.z(), -length / 2), length / 2);  // caps move rigidly
  const double theta = t / radius, rest = p.z() - t;
  const double r = radius + p.x();
  return Point(r * std::cos(theta) - radius - rest * std::sin(theta), p.y(), r * std::sin(theta) + rest * std::cos(theta));
}

double mean_edge_length(const Mesh& m)
{
  double sum = 0;
  for(auto e : m.edges()) sum += std::sqrt(CGAL::squared_distance(m.point(m.vertex(e, 0)), m.point(m.vertex(e, 1))));
  return sum / static_cast<double>(m.number_of_edges());
}

/// Relative change of the edge lengths of `a` in `b` (same connectivity): mean and maximum.
std::pair<double, double> edge_distortion(const Mesh& a, const Mesh& b)
{
  double sum = 0, maximum = 0;
  for(auto e : a.edges())
  {
    const double la = std::sqrt(CGAL::squared_distance(a.point(a.vertex(e, 0)), a.point(a.vertex(e, 1))));
    const double lb = std::sqrt(CGAL::squared_distance(b.point(b.vertex(e, 0)), b.point(b.vertex(e, 1))));
    const double d = std::abs(lb / la - 1);
    sum += d;
    maximum = std::max(maximum, d);
  }
  return {sum / static_cast<double>(a.number_of_edges()), maximum};
}

/// For every vertex of `query` (positions on the surface of `surface`), the vertex of `surface`
/// nearest to it within its face (the corner of largest barycentric coordinate).
Vertex_map nearest_corners(const Mesh& query, const Mesh& surface)
{
  typedef CGAL::AABB_face_graph_triangle_primitive<Mesh> Primitive;
  typedef CGAL::AABB_traits<Kernel, Primitive> Traits;
  typedef CGAL::AABB_tree<Traits> Tree;
  Tree tree(faces(surface).first, faces(surface).second, surface);
  tree.accelerate_distance_queries();
  Vertex_map out(num_vertices(query));
  for(Mesh::Vertex_index w : query.vertices())
  {
    const auto location = CGAL::Polygon_mesh_processing::locate_with_AABB_tree(query.point(w), tree, surface);
    Mesh::Halfedge_index h = surface.halfedge(location.first);
    int best = 0;
    for(int c = 1; c < 3; ++c)
      if(location.second[c] > location.second[best]) best = c;
    // The coordinates follow source(h), target(h), target(next(h)).
    for(int c = 0; c < best; ++c) h = surface.next(h);
    out[w.idx()] = surface.source(h).idx();
  }
  return out;
}

std::string shell_quote(const std::string& s)
{
  std::string out = "'";
  for(char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

/// Extracts data/meshes/homer.off of libcgal-demo's data archive into `file`, atomically (a
/// temporary file renamed into place only when tar succeeded). False when it cannot.
bool extract_homer(const std::string& file)
{
  const std::string command = "tar -xzf " + shell_quote(cgal_demo_data) + " -O data/meshes/homer.off 2>/dev/null";
  FILE* tar = ::popen(command.c_str(), "r");
  if(!tar) return false;
  try
  {
    smc::Atomic_output_file out(file);
    char buffer[1 << 16];
    std::size_t n = 0, total = 0;
    while((n = std::fread(buffer, 1, sizeof(buffer), tar)) > 0)
    {
      out.stream().write(buffer, std::streamsize(n));
      total += n;
    }
    const int status = ::pclose(tar);
    tar = nullptr;
    if(status != 0 || total == 0) return false;
    out.commit();
    return true;
  }
  catch(const smc::IO_error&)
  {
    if(tar) ::pclose(tar);
    return false;
  }
}

struct Quality
{
  smc::Error_statistics e12, e21;
  smc::Cycle_consistency c1, c2;
  std::size_t inconsistent = 0;
  double mean() const { return 0.5 * (e12.mean + e21.mean); }
  double within(double t) const { return 0.5 * (e12.fraction_below(t) + e21.fraction_below(t)); }
  double fixed_points() const { return 0.5 * (c1.fixed_point_fraction + c2.fixed_point_fraction); }
};

Quality evaluate(const Evaluator& a, const Evaluator& b, const Vertex_map& m12, const Vertex_map& m21,
                 const Vertex_map& gt12, const Vertex_map& gt21)
{
  Vertex_map all_a(m12.size()), all_b(m21.size());
  for(std::size_t i = 0; i < all_a.size(); ++i) all_a[i] = i;
  for(std::size_t i = 0; i < all_b.size(); ++i) all_b[i] = i;
  Quality q;
  q.e12 = b.geodesic_errors(m12, all_a, gt12);
  q.e21 = a.geodesic_errors(m21, all_b, gt21);
  q.c1 = a.cycle_consistency(m12, m21);
  q.c2 = b.cycle_consistency(m21, m12);
  q.inconsistent = smc::number_of_inconsistent_vertices(m12, m21);
  return q;
}

std::vector<double> mean_curve(const std::vector<double>& a, const std::vector<double>& b)
{
  std::vector<double> out(a.size());
  for(std::size_t i = 0; i < a.size(); ++i) out[i] = 0.5 * (a[i] + b[i]);
  return out;
}

} // namespace

int run_demo(int argc, char** argv)
{
  smc::Matching_settings settings;
  Common_options common;
  std::string out = "comap_demo";
  bool generated = false;
  Option_parser p("demo", "comap demo [--out DIR] [options]",
                  "Runs the whole pipeline (automatic initial maps, coupled refinement, evaluation, colour transfer, "
                  "plots) on Homer from the Debian package libcgal-demo and a second pose of it (arms and head moved, "
                  "then remeshed), whose ground truth is known from the construction. Without libcgal-demo (or with "
                  "--generated), on a generated bumpy capsule and a bent, remeshed copy.");
  p.section("Demo");
  p.value("--out", "DIR", "output directory (created)", out, [&](const std::string& v) { out = v; });
  p.flag("--generated", "use the generated capsule pair even when libcgal-demo is installed", [&] { generated = true; });
  p.section("Settings");
  add_settings_options(p, settings);
  add_common_options(p, common);
  bool run = true;
  const std::vector<std::string> extra = p.parse(argc, argv, 2, run);
  if(!run) return 0;
  if(!extra.empty()) throw Usage_error("unexpected argument " + extra.front());
  make_directories(out);
  const Thread_limit limit(common.threads);
  const Progress progress(common.quiet);
  const Stopwatch total;

  // ------------------------------------------------------------ the pair
  Mesh source;
  std::string source_name, source_description;
  std::function<Point(const Point&)> pose;
  if(!generated && file_exists(cgal_demo_data))
  {
    source_name = "homer.off";
    const std::string file = out + "/" + source_name;
    if(extract_homer(file))
    {
      try
      {
        source = read_triangle_mesh(file);
        source_description = "Homer (data/meshes/homer.off of libcgal-demo)";
        pose = pose_homer;
      }
      catch(const std::exception& e)
      {
        progress.line(std::string("cannot use homer.off from libcgal-demo (") + one_line(e.what()) +
                      "); using a generated shape");
      }
    }
    else
      progress.line(std::string("cannot extract data/meshes/homer.off from ") + cgal_demo_data + "; using a generated shape");
  }
  else if(!generated)
    progress.line(std::string("libcgal-demo is not installed (no ") + cgal_demo_data + "); using a generated shape");
  if(!pose)
  {
    source_name = "capsule.off";
    source = bumpy_capsule();
    write_off(out + "/" + source_name, source);
    source_description = "a generated bumpy capsule";
    pose = bend_capsule;
  }
  const std::string target_name = stem(source_name) + "_posed.off";
  Mesh posed = source;
  for(Mesh::Vertex_index v : posed.vertices()) posed.point(v) = pose(source.point(v));
  const std::pair<double, double> distortion = edge_distortion(source, posed);
  Mesh target = posed;
  CGAL::Polygon_mesh_processing::isotropic_remeshing(faces(target), mean_edge_length(source), target,
                                                     CGAL::parameters::number_of_iterations(3));
  target.collect_garbage();
  write_off(out + "/" + target_name, target);
  // Ground truth: source vertex i sits at posed.point(i) in the target's pose.
  const Vertex_map gt12 = nearest_corners(posed, target), gt21 = nearest_corners(target, posed);
  write_vertex_map(out + "/ground_truth_12.map", gt12, 1);
  write_vertex_map(out + "/ground_truth_21.map", gt21, 1);
  progress.line("source " + source_name + " (" + std::to_string(num_vertices(source)) + " vertices); target " +
                target_name + ": posed (edge lengths change by " + percent(distortion.first) + " on average, " +
                percent(distortion.second) + " at most) and remeshed (" + std::to_string(num_vertices(target)) +
                " vertices)");

  // ------------------------------------------------------------ the pipeline
  Progress_visitor visitor(progress);
  Vertex_map m12, m21;
  // The meshes as written (the files round their coordinates): the maps are those of
  // `comap match` on the two files.
  const smc::Triangle_soup a = read_mesh_soup(out + "/" + source_name), b = read_mesh_soup(out + "/" + target_name);
  const smc::Matching_result r = match_soups(
      a, b, nullptr, nullptr, smc::parameters::matching_settings(settings, smc::parameters::visitor(std::ref(visitor))),
      m12, m21);
  const Vertex_map& initial12 = r.unrefined_map_12;
  write_vertex_map(out + "/initial_12.map", r.unrefined_map_12, 1);
  write_vertex_map(out + "/initial_21.map", r.unrefined_map_21, 1);
  write_vertex_map(out + "/final_12.map", m12, 1);
  write_vertex_map(out + "/final_21.map", m21, 1);
  const Evaluator on_source(source), on_target(target);
  const Quality before = evaluate(on_source, on_target, r.unrefined_map_12, r.unrefined_map_21, gt12, gt21);
  const Quality after = evaluate(on_source, on_target, m12, m21, gt12, gt21);

  // ------------------------------------------------------------ pictures
  const std::vector<Color> colors = coordinate_colors(b);
  write_colored_ply(out + "/target_colors.ply", b, colors);
  write_colored_ply(out + "/source_final.ply", a, pull_colors(colors, m12));
  write_colored_ply(out + "/source_initial.ply", a, pull_colors(colors, initial12));
  write_colored_ply(out + "/source_ground_truth.ply", a, pull_colors(colors, gt12));
  Plot errors;
  errors.title = "Cumulative geodesic error, both directions, all vertices";
  errors.x_label = "geodesic error / sqrt(area)";
  errors.y_label = "fraction of vertices";
  errors.x_max = before.e12.thresholds.back();
  errors.series.push_back({"automatic initial maps", before.e12.thresholds, mean_curve(before.e12.cumulative, before.e21.cumulative),
                           series_color(6), true, false});
  errors.series.push_back({"final maps", after.e12.thresholds, mean_curve(after.e12.cumulative, after.e21.cumulative),
                           series_color(0), false, false});
  write_svg(out + "/cumulative_error.svg", errors);
  Plot cycle = errors;
  cycle.title = "Cycle consistency: distance from x to T21(T12(x))";
  cycle.x_label = "geodesic distance / sqrt(area)";
  cycle.series[0].y = mean_curve(before.c1.distances.cumulative, before.c2.distances.cumulative);
  cycle.series[1].y = mean_curve(after.c1.distances.cumulative, after.c2.distances.cumulative);
  write_svg(out + "/cycle_consistency.svg", cycle);
  const double total_seconds = total.seconds();
  {
    smc::Atomic_output_file summary(out + "/summary.json");
    Json_writer json(summary.stream());
    json.begin_object().value("source", source_name).value("target", target_name);
    json.value("mean_edge_distortion", distortion.first).value("maximum_edge_distortion", distortion.second);
    write_settings(json, "settings", settings, smc::Map_origin::automatic);
    write_result(json, "result", r);
    for(const auto& q : {std::make_pair("automatic", &before), std::make_pair("final", &after)})
    {
      json.begin_object(q.first);
      write_error_statistics(json, "errors_12", q.second->e12, true);
      write_error_statistics(json, "errors_21", q.second->e21, true);
      json.value("fixed_points_source", q.second->c1.fixed_point_fraction)
          .value("fixed_points_target", q.second->c2.fixed_point_fraction)
          .value("inconsistent_vertices", q.second->inconsistent)
          .end_object();
    }
    json.value("total_seconds", total_seconds).end_object().finish();
    commit_outputs({&summary});
  }

  const std::size_t n = num_vertices(source) + num_vertices(target);
  std::cout << "comap demo: " << source_description << ", " << num_vertices(source) << " vertices, and a second pose of it\n"
            << "(moved near-isometrically, edge lengths changed by " << percent(distortion.first)
            << " on average, then remeshed: " << num_vertices(target) << " vertices); ground truth from the construction.\n"
            << "Errors: geodesic distance to the true match / sqrt(area), both directions, all vertices.\n\n"
            << "                          mean error  within 0.025  within 0.05  fixed points  inconsistent\n";
  for(const auto& row : {std::make_pair("automatic initial maps", &before), std::make_pair("final maps", &after)})
  {
    char line[200];
    std::snprintf(line, sizeof(line), "%-24s  %10.4f  %12s  %11s  %12s  %6zu of %zu\n", row.first, row.second->mean(),
                  percent(row.second->within(0.025)).c_str(), percent(row.second->within(0.05)).c_str(),
                  percent(row.second->fixed_points()).c_str(), row.second->inconsistent, n);
    std::cout << line;
  }
  std::cout << "\n";
  for(const std::string& d : r.decisions) std::cout << d << "\n";
  std::cout << confidence_report(r);
  std::cout << "\ntimings:";
  for(int s = 0; s <= int(smc::Matching_stage::selection); ++s)
    if(r.stage_seconds[std::size_t(s)] > 0)
      std::cout << (s == 0 ? " " : ", ") << smc::to_string(smc::Matching_stage(s)) << " "
                << duration(r.stage_seconds[std::size_t(s)]);
  std::cout << "; match_shapes() " << duration(r.total_seconds) << ", total " << duration(total_seconds) << "\n";
  std::cout << "\n"
            << "outputs in " << out << "/:\n"
            << "  " << source_name << ", " << target_name << "   the two meshes\n"
            << "  final_12.map, final_21.map       the maps (1-based; also initial_*.map, ground_truth_*.map)\n"
            << "  target_colors.ply                the second pose coloured by position\n"
            << "  source_final.ply                 the source coloured through the final map (compare with\n"
            << "                                   source_initial.ply and source_ground_truth.ply in MeshLab)\n"
            << "  cumulative_error.svg, cycle_consistency.svg, summary.json\n";
  return 0;
}

} // namespace comap
