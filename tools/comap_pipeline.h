// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// comap: the matching pipeline on top of the library: preparing a shape once (spectrum shared by
// the automatic initialisation and the descriptor stack), automatic initial maps, the coupled
// refinement with progress lines, and JSON records of what happened.

#ifndef SMC_TOOLS_COMAP_PIPELINE_H
#define SMC_TOOLS_COMAP_PIPELINE_H

#include "comap_json.h"
#include "comap_mesh_io.h"
#include "comap_settings.h"

#include <CGAL/Surface_mesh_correspondence/Correspondence_shape.h>
#include <CGAL/Surface_mesh_correspondence/automatic_initialization.h>
#include <CGAL/Surface_mesh_correspondence/evaluation.h>
#include <CGAL/Surface_mesh_correspondence/refine_coupled_maps.h>

#include <memory>
#include <string>

namespace comap {

typedef smc::Correspondence_shape<Mesh, Concurrency> Shape;
typedef smc::Map_evaluator<Concurrency> Evaluator;

/// A mesh prepared once for everything a run needs: the refinement's Correspondence_shape
/// and/or the automatic initialisation's spectrum and descriptors, on one flat copy. One
/// eigensolve serves both when the refinement needs at most the initialisation's eigenpairs on
/// the same operator (the defaults: 100 of 200): the refinement takes the leading eigenpairs.
/// Otherwise each computes its own, so that the initialisation's maps are exactly those of
/// automatic_initial_maps().
class Prepared_shape
{
public:
  std::string name;  ///< the file (or label) used in messages
  Mesh mesh;
  /// The refinement's data (null when the run does not refine).
  std::unique_ptr<Shape> shape;
  /// The initialisation's descriptors (empty when the run is given initial maps).
  Eigen::MatrixXd initialization_descriptors;
  smc::Shape_preprocessing_times times;      ///< flat copy, spectrum, descriptor stack, distances
  double initialization_seconds = 0;         ///< the initialisation's own spectrum (if any) and descriptors
  double total_seconds = 0;                  ///< all of the preparation
  /// True when the refinement's spectrum is the leading part of the initialisation's (one
  /// eigensolve; its time is in `initialization_seconds`).
  bool spectrum_from_initialization = false;

  const smc::internal::Indexed_mesh& indexed_mesh() const { return shape ? shape->data().mesh : *own_mesh_; }
  /// The spectrum of the initialisation.
  const smc::Laplace_beltrami_spectrum& initialization_spectrum() const
  {
    return own_spectrum_ ? *own_spectrum_ : shape->data().largest_spectrum();
  }
  std::size_t number_of_vertices() const { return num_vertices(mesh); }
  /// An evaluator of maps into this shape (built on first use; not thread-safe).
  const Evaluator& evaluator() const;

private:
  friend std::unique_ptr<Prepared_shape> prepare_shape(const std::string&, Mesh, const Settings&, bool, bool,
                                                       const Progress&);
  std::unique_ptr<smc::internal::Indexed_mesh> own_mesh_;
  std::shared_ptr<const smc::Laplace_beltrami_spectrum> own_spectrum_;
  mutable std::unique_ptr<Evaluator> evaluator_;
};

/// Prepares `mesh` for the refinement (`for_refinement`) and/or the automatic initialisation
/// (`for_initialization`), printing one progress line.
std::unique_ptr<Prepared_shape> prepare_shape(const std::string& name, Mesh mesh, const Settings& settings,
                                              bool for_refinement, bool for_initialization,
                                              const Progress& progress);

/// Automatic initial maps between two prepared shapes (prepared with `for_initialization`).
smc::Automatic_initialization_result initialize_maps(const Prepared_shape& a, const Prepared_shape& b,
                                                     const Settings& settings, Vertex_map& map_12,
                                                     Vertex_map& map_21);
/// The tear repair of the automatic initialisation applied to given maps (see
/// smc::repair_torn_maps(); `repair_tears` false: none), then, with
/// settings.initialization.compare_with_automatic_maps, the comparison with the automatic maps
/// (smc::compare_with_automatic_maps()); the shapes must be prepared for the initialisation.
smc::Automatic_initialization_result repair_maps(const Prepared_shape& a, const Prepared_shape& b,
                                                 const Settings& settings, Vertex_map& map_12, Vertex_map& map_21,
                                                 bool repair_tears);
/// One progress line describing an initialisation or repair result.
std::string initialization_summary(const smc::Automatic_initialization_result& r);

/// Whether repair_maps() returned maps of the automatic initialisation (the automatic maps of
/// --compare-automatic, or a kept repair pass, whose maps are ZoomOut maps steered by landmarks
/// from the given maps' core) rather than the given maps: such maps are refined with the preset
/// for automatic maps.
bool repaired_maps_are_automatic(const smc::Automatic_initialization_result& r);

/// The coupled refinement of `map_12` and `map_21` in place, with one progress line per MRF
/// solve prefixed by `label`. `automatic_input`: the maps come from initialize_maps() (see
/// Settings::keep_consistent_input_maps).
smc::Coupled_refinement_result refine_maps(const Prepared_shape& a, const Prepared_shape& b, Vertex_map& map_12,
                                           Vertex_map& map_21, const Settings& settings, bool automatic_input,
                                           const Progress& progress, const std::string& label = "");

/// "spectrum 1.2 s, descriptors 0.8 s, distances 1.1 s"
std::string preparation_summary(const Prepared_shape& s);

void write_preparation(Json_writer& json, const std::string& key, const Prepared_shape& s);
void write_initialization(Json_writer& json, const std::string& key, const smc::Automatic_initialization_result& r);
void write_refinement(Json_writer& json, const std::string& key, const smc::Coupled_refinement_result& r);
/// Mean, median, maximum, fractions within 0.025 / 0.05 / 0.1 and, with `with_curve`, the
/// cumulative curve.
void write_error_statistics(Json_writer& json, const std::string& key, const smc::Error_statistics& e,
                            bool with_curve);

} // namespace comap

#endif // SMC_TOOLS_COMAP_PIPELINE_H
