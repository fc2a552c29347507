// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// comap: how the commands report a run: the progress lines of match_shapes() (a visitor of the
// library's stage events) and the JSON records of its result and of error statistics.

#ifndef SMC_TOOLS_COMAP_REPORT_H
#define SMC_TOOLS_COMAP_REPORT_H

#include "comap_common.h"
#include "comap_json.h"

#include <CGAL/Surface_mesh_correspondence/evaluation.h>
#include <CGAL/Surface_mesh_correspondence/match_shapes.h>

#include <string>

namespace comap {

/// The progress lines of a run: one per stage begun and ended, one per refinement solve, and the
/// stages' progress at most every few seconds. Lines are prefixed by `label`.
class Progress_visitor : public smc::Default_matching_visitor
{
public:
  explicit Progress_visitor(const Progress& progress, std::string label = "", bool steps = true)
      : progress_(&progress), label_(std::move(label)), steps_(steps)
  {}
  bool stage_begun(smc::Matching_stage s);
  bool progress(smc::Matching_stage s, double fraction);
  bool stage_ended(smc::Matching_stage s, double seconds);
  bool refinement_step(const smc::Refinement_step& s);

private:
  const Progress* progress_;
  std::string label_;
  bool steps_;
  double last_line_ = -1e9;
};

/// Writes what the input check found in a mesh (Mesh_irregularities) as the object `key`: the
/// counts and the indices (`index_base`: the numbering of the map files), vertices of an edge in
/// increasing order, faces numbered in the file's order.
void write_irregularities(Json_writer& json, const std::string& key, const smc::Mesh_irregularities& r,
                          int index_base);

/// The lines --verbose prints on stderr about a mesh `file`: what the input check found, with the
/// indices (at most `shown` of each kind), or that it found nothing.
std::string irregularities_report(const std::string& file, const smc::Mesh_irregularities& r, int index_base,
                                  std::size_t shown = 20);

/// Writes the result of match_shapes() (decisions, stage times, consistency and distortion,
/// refinement solves) as a JSON object named `key`.
void write_result(Json_writer& json, const std::string& key, const smc::Matching_result& r);

/// The confidence line of the standard output ("confidence: 0.97 (lowest: ...)"); when the
/// confidence is low, also writes a warning on stderr (whatever --quiet says).
std::string confidence_report(const smc::Matching_result& r);

/// Mean, median, maximum, fractions within 0.025 / 0.05 / 0.1 and, with `with_curve`, the
/// cumulative curve.
void write_error_statistics(Json_writer& json, const std::string& key, const smc::Error_statistics& e,
                            bool with_curve);

} // namespace comap

#endif // SMC_TOOLS_COMAP_REPORT_H
