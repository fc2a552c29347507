// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#include "comap_report.h"

#include <algorithm>
#include <functional>
#include <iostream>

namespace comap {

namespace {

const char* stage_title(smc::Matching_stage s)
{
  switch(s)
  {
  case smc::Matching_stage::validation: return "checking the inputs";
  case smc::Matching_stage::preparation: return "preparing the shapes (spectra, descriptors, geodesic distances)";
  case smc::Matching_stage::initialization: return "computing automatic initial maps (functional maps + ZoomOut)";
  case smc::Matching_stage::repair: return "repairing the tears of the given maps";
  case smc::Matching_stage::comparison: return "comparing the given maps with the automatic maps";
  case smc::Matching_stage::refinement: return "coupled refinement";
  case smc::Matching_stage::selection: return "selecting where the refined maps replace their input";
  }
  return "";
}

} // namespace

bool Progress_visitor::stage_begun(smc::Matching_stage s)
{
  if(s != smc::Matching_stage::validation) progress_->line(label_ + stage_title(s));
  last_line_ = progress_->elapsed();
  return true;
}

bool Progress_visitor::progress(smc::Matching_stage s, double fraction)
{
  const double now = progress_->elapsed();
  if(now - last_line_ < 2.0) return true;
  last_line_ = now;
  progress_->line(label_ + "  " + smc::to_string(s) + " " + percent(fraction));
  return true;
}

bool Progress_visitor::stage_ended(smc::Matching_stage s, double seconds)
{
  if(s != smc::Matching_stage::validation) progress_->line(label_ + smc::to_string(s) + " done in " + duration(seconds));
  return true;
}

bool Progress_visitor::refinement_step(const smc::Refinement_step& s)
{
  if(!steps_) return true;
  progress_->line(label_ + "  refinement " + std::to_string(s.outer_iteration + 1) +
                  (s.direction == 0 ? ", map 1->2, " : ", map 2->1, ") + std::to_string(s.rings) +
                  (s.rings == 1 ? " ring" : " rings") + ": energy " + significant(s.energy) + " (bound " +
                  significant(s.lower_bound) + ", " + std::to_string(s.trws_iterations) + " TRW-S iterations), " +
                  std::to_string(s.changed_vertices) + " matches changed, " + std::to_string(s.inconsistent_vertices) +
                  " inconsistent; data " + duration(s.data_preparation_seconds) + ", TRW-S " +
                  duration(s.trws_seconds));
  return true;
}

namespace {

void write_diagnostics_fields(Json_writer& json, const smc::Map_diagnostics& d)
{
  json.value("vertices", d.vertices)
      .value("inconsistent_fraction", d.inconsistent_fraction)
      .value("cycle_error", d.cycle_error)
      .value("distortion", d.distortion)
      .value("distortion_samples", d.distortion_samples)
      .value("global_distortion", d.global_distortion)
      .value("descriptor_distance", d.descriptor_distance)
      .value("orientation_reversal", d.orientation_reversal)
      .value("global_orientation_reversal", d.global_orientation_reversal)
      .value("energy", d.energy);
}

/// "diagnostics": {"map_12": {"before": {..., "regions": [{...}, ...]}, "after": {...}}, "map_21": ...}
void write_diagnostics(Json_writer& json, const smc::Matching_diagnostics& diagnostics)
{
  json.begin_object("diagnostics");
  for(int direction = 0; direction < 2; ++direction)
  {
    json.begin_object(direction == 0 ? "map_12" : "map_21");
    for(int phase = 0; phase < 2; ++phase)
    {
      const smc::Direction_diagnostics& d = phase == 0 ? diagnostics.before[direction] : diagnostics.after[direction];
      json.begin_object(phase == 0 ? "before" : "after");
      write_diagnostics_fields(json, d.whole);
      json.begin_array("regions");
      for(const smc::Map_diagnostics& region : d.regions)
      {
        json.begin_object();
        write_diagnostics_fields(json, region);
        json.end_object();
      }
      json.end_array().end_object();
    }
    json.end_object();
  }
  json.end_object();
}

} // namespace

std::string confidence_report(const smc::Matching_result& r)
{
  const smc::Matching_confidence& c = r.confidence;
  if(c.low)
    std::cerr << "comap: warning: low confidence " << fixed(c.score, 2) << " (" << c.reason
              << "): the maps are probably wrong as a whole (a mirror image, or parts sent to other parts); "
                 "landmarks (--landmarks) or initial maps can guide them\n";
  return "confidence: " + fixed(c.score, 2) + (c.low ? " (low: " : " (lowest: ") + c.reason + ")\n";
}

void write_irregularities(Json_writer& json, const std::string& key, const smc::Mesh_irregularities& r,
                          int index_base)
{
  const std::size_t b = std::size_t(index_base);
  json.begin_object(key)
      .value("non_manifold_edges", r.non_manifold_edges.size())
      .value("non_manifold_vertices", r.non_manifold_vertices.size())
      .value("degenerate_faces", r.degenerate_faces.size());
  // The index lists on one line each.
  auto list = [](std::size_t count, const std::function<std::string(std::size_t)>& item) {
    std::string text = "[";
    for(std::size_t k = 0; k < count; ++k) text += (k ? ", " : "") + item(k);
    return text + "]";
  };
  json.raw_value("non_manifold_edge_vertices", list(r.non_manifold_edges.size(), [&](std::size_t k) {
    return "[" + std::to_string(r.non_manifold_edges[k][0] + b) + ", " + std::to_string(r.non_manifold_edges[k][1] + b) +
           "]";
  }));
  json.raw_value("non_manifold_vertex_indices", list(r.non_manifold_vertices.size(), [&](std::size_t k) {
    return std::to_string(r.non_manifold_vertices[k] + b);
  }));
  json.raw_value("degenerate_face_indices", list(r.degenerate_faces.size(), [&](std::size_t k) {
    return std::to_string(r.degenerate_faces[k] + b);
  }));
  json.end_object();
}

std::string irregularities_report(const std::string& file, const smc::Mesh_irregularities& r, int index_base,
                                  std::size_t shown)
{
  if(r.empty()) return file + ": manifold, no face of zero area\n";
  const std::size_t b = std::size_t(index_base);
  std::string out;
  auto list = [&](std::size_t count, const char* one, const char* several,
                  const std::function<std::string(std::size_t)>& item) {
    if(count == 0) return;
    out += file + ": " + std::to_string(count) + " " + (count == 1 ? one : several) + ":";
    for(std::size_t k = 0; k < std::min(count, shown); ++k) out += " " + item(k);
    if(count > shown) out += " ... (" + std::to_string(count - shown) + " more)";
    out += "\n";
  };
  list(r.non_manifold_edges.size(), "non-manifold edge (in more than two faces)",
       "non-manifold edges (in more than two faces)", [&](std::size_t k) {
    return "(" + std::to_string(r.non_manifold_edges[k][0] + b) + ", " + std::to_string(r.non_manifold_edges[k][1] + b) +
           ")";
  });
  list(r.non_manifold_vertices.size(), "non-manifold vertex (joining separate fans of faces)",
       "non-manifold vertices (joining separate fans of faces)",
       [&](std::size_t k) { return std::to_string(r.non_manifold_vertices[k] + b); });
  list(r.degenerate_faces.size(), "face of zero area", "faces of zero area", [&](std::size_t k) { return std::to_string(r.degenerate_faces[k] + b); });
  out += file + ": matched with the tufted Laplacian" + std::string(r.degenerate_faces.empty() ? "" : " and mollification") +
         " (" + std::to_string(index_base) + "-based indices)\n";
  return out;
}

void write_result(Json_writer& json, const std::string& key, const smc::Matching_result& r)
{
  auto origin = [](smc::Map_origin o) { return o == smc::Map_origin::automatic ? "automatic" : "given"; };
  json.begin_object(key)
      .value("initial_maps", origin(r.initial_maps))
      .value("refined_maps", origin(r.refined_maps))
      .value("used_landmarks", r.used_landmarks)
      .value("repaired", r.repaired)
      .value("repair_passes", r.repair_passes)
      .value("compared", r.compared)
      .value("automatic_maps_computed", r.automatic_maps_computed)
      .value("automatic_maps_kept", r.automatic_maps_kept)
      .value("given_maps_distortion", r.given_maps_distortion)
      .value("automatic_maps_distortion", r.automatic_maps_distortion)
      .value("refined", r.refined)
      .value("termination", smc::to_string(r.termination));
  json.begin_array("decisions");
  for(const std::string& d : r.decisions) json.element(d);
  json.end_array();
  json.begin_object("selection")
      .value("refined_more_consistent", r.selection.refined_more_consistent)
      .value("refined_fraction_12", r.selection.refined_fraction_12)
      .value("refined_fraction_21", r.selection.refined_fraction_21)
      .value("input_distortion", r.selection.input_distortion)
      .value("refined_distortion", r.selection.refined_distortion)
      .value("selected_distortion", r.selection.selected_distortion)
      .value("inconsistent_input", r.selection.inconsistent_input)
      .value("inconsistent_refined", r.selection.inconsistent_refined)
      .value("inconsistent_selected", r.selection.inconsistent_selected)
      .end_object();
  json.value("inconsistent_vertices_before", r.inconsistent_vertices_before)
      .value("inconsistent_vertices_after", r.inconsistent_vertices_after)
      .value("cycle_error_before", r.cycle_error_before)
      .value("cycle_error_after", r.cycle_error_after)
      .value("distortion_before", r.distortion_before)
      .value("distortion_after", r.distortion_after);
  if(r.diagnostics.computed) write_diagnostics(json, r.diagnostics);
  json.begin_object("confidence")
      .value("score", r.confidence.score)
      .value("score_12", r.confidence.direction_scores[0])
      .value("score_21", r.confidence.direction_scores[1])
      .value("low", r.confidence.low)
      .value("reason", r.confidence.reason)
      .end_object();
  json.begin_object("initialization")
      .value("functional_map_seconds", r.initialization.functional_map_seconds)
      .value("zoomout_seconds", r.initialization.zoomout_seconds)
      .value("orientation_sign", r.initialization.orientation_sign)
      .value("orientation_agreement", r.initialization.orientation_agreement)
      .value("torn_fraction_before", r.initialization.torn_fraction_before)
      .value("torn_fraction", r.initialization.torn_fraction)
      .value("sample_distortion", r.initialization.sample_distortion)
      .value("extremities_1", r.initialization.extremities_1)
      .value("extremities_2", r.initialization.extremities_2)
      .value("extremity_hypotheses", r.initialization.extremity_hypotheses)
      .value("extremity_hypothesis", r.initialization.extremity_hypothesis)
      .value("extremity_seconds", r.initialization.extremity_seconds)
      .value("passes", r.initialization.passes)
      .end_object();
  json.begin_object("stage_seconds");
  for(int s = 0; s <= int(smc::Matching_stage::selection); ++s)
    json.value(smc::to_string(smc::Matching_stage(s)), r.stage_seconds[std::size_t(s)]);
  json.value("total", r.total_seconds).end_object();
  json.begin_object("refinement")
      .value("outer_iterations", r.refinement.outer_iterations)
      .value("kept_outer_iterations", r.refinement.kept_outer_iterations)
      .value("data_preparation_seconds", r.refinement.data_preparation_seconds)
      .value("trws_seconds", r.refinement.trws_seconds);
  json.begin_array("steps");
  for(const smc::Refinement_step& s : r.refinement.steps)
    json.begin_object()
        .value("outer_iteration", s.outer_iteration)
        .value("direction", s.direction == 0 ? "1->2" : "2->1")
        .value("rings", s.rings)
        .value("energy", s.energy)
        .value("lower_bound", s.lower_bound)
        .value("trws_iterations", s.trws_iterations)
        .value("changed_vertices", s.changed_vertices)
        .value("inconsistent_vertices", s.inconsistent_vertices)
        .value("data_preparation_seconds", s.data_preparation_seconds)
        .value("trws_seconds", s.trws_seconds)
        .end_object();
  json.end_array();
  json.end_object();
  json.end_object();
}

void write_error_statistics(Json_writer& json, const std::string& key, const smc::Error_statistics& e,
                            bool with_curve)
{
  json.begin_object(key)
      .value("samples", e.errors.size())
      .value("mean", e.mean)
      .value("median", e.median)
      .value("maximum", e.maximum)
      .value("fraction_within_0.025", e.fraction_below(0.025))
      .value("fraction_within_0.05", e.fraction_below(0.05))
      .value("fraction_within_0.1", e.fraction_below(0.1));
  if(with_curve) json.value("thresholds", e.thresholds).value("cumulative", e.cumulative);
  json.end_object();
}

} // namespace comap
