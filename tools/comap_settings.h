// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// comap: every algorithm parameter of the library as a command-line option. The defaults shown
// by --help are read from the library's own settings structs (Refinement_settings,
// Shape_settings, Descriptor_settings, Initialization_settings), never copied.

#ifndef SMC_TOOLS_COMAP_SETTINGS_H
#define SMC_TOOLS_COMAP_SETTINGS_H

#include "comap_json.h"
#include "comap_options.h"

#include <CGAL/Surface_mesh_correspondence/automatic_initialization.h>
#include <CGAL/Surface_mesh_correspondence/refine_coupled_maps.h>

namespace comap {

namespace smc = CGAL::Surface_mesh_correspondence;

/// The parameters of a whole matching run.
struct Settings
{
  smc::internal::Shape_settings shape;                 ///< spectrum, descriptor stack, distance oracle
  smc::Refinement_settings refinement;                  ///< Algorithm 1
  smc::internal::Initialization_settings initialization; ///< automatic initial maps
  /// Refinement_settings::keep_consistent_input_maps: 1 on (the paper's rule), 0 off, -1
  /// automatic (the default: on for given initial maps, off for automatic ones). Automatic maps
  /// are refined with a lighter cycle term (automatic_consistency_weight) whose first iterate is
  /// often a little less consistent than they are but more accurate; the paper's rule would
  /// return them unchanged (TOSCA_r, every 8th pair: 0.0232 refined against 0.0260 kept).
  int keep_consistent_input_maps = -1;
  /// Refinement_settings::stop_when_consistency_worsens: 1 consistency (the paper's Eq. (4) early
  /// stop), 0 none (run the whole ring schedule), -1 automatic (the default): the early stop for
  /// automatic initial maps (with the cycle term their iterates grow more consistent, so it only
  /// ends a schedule that stops helping); the whole schedule for given maps, where later iterates
  /// become the most consistent (TOSCA_r WKS maps: 0.0454 against 0.0460).
  int stop_rule = -1;
  /// The refinement of automatic initial maps when --rings, --candidates and --trws-iterations
  /// are not given: they lie within a few rings of their refined positions, so a short schedule
  /// suffices, and with twice the paper's candidates it searches those rings more finely. All 284
  /// TOSCA_r pairs, refinement of the same automatic maps: 40 candidates, rings 4, 3, 2, 1 give
  /// 0.0248 (15 TRW-S iterations per solve, the same as 100), 20 candidates, rings 3, 2, 1 0.0257;
  /// with m = 20 the wider rings are worse (0.0240 against 0.0237 on every 4th pair). The solves
  /// of these maps start near their optimum: 15 iterations reach it (TOSCA_r, every 4th pair,
  /// 0.0227 with 15 and with up to 100) in half the time.
  std::vector<int> automatic_ring_schedule{4, 3, 2, 1};
  bool ring_schedule_given = false;  ///< --rings was given: it applies to every kind of maps
  int automatic_number_of_candidates = 40;  ///< see automatic_ring_schedule
  bool number_of_candidates_given = false;  ///< --candidates was given
  int automatic_trws_number_of_iterations = 15;  ///< see automatic_ring_schedule
  bool trws_number_of_iterations_given = false;  ///< --trws-iterations was given
  /// The cycle term's weight for automatic initial maps when --consistency-weight is not given:
  /// they are consistent already, and a lighter cycle term lets the refinement move them further
  /// (TOSCA_r, every 8th pair, schedule 3, 2, 1: 0.0232 against 0.0239 with 1, cycle error 0.0065
  /// against 0.0041). Given maps keep Refinement_settings::consistency_weight (1): from the
  /// WKS maps the cycle term is what removes their inconsistencies.
  double automatic_consistency_weight = 0.5;
  bool consistency_weight_given = false;  ///< --consistency-weight was given
};

/// The value of an automatic switch of Settings (1 on, 0 off, -1 automatic) for initial maps that
/// are automatic or given: `when_automatic` when the switch is automatic.
inline bool resolve_switch(int choice, bool when_automatic) { return choice < 0 ? when_automatic : choice == 1; }

/// The refinement settings with the automatic choices (keep-input, stop rule, ring schedule,
/// candidates, TRW-S iterations, cycle term weight)
/// resolved for initial maps that are automatic or given.
smc::Refinement_settings resolved_refinement(const Settings& settings, bool automatic_input);

/// Registers the options of every algorithm parameter (refinement, shape preparation and, when
/// `with_initialization`, automatic initialisation) on `parser`, writing into `settings`.
void add_algorithm_options(Option_parser& parser, Settings& settings, bool with_initialization);

/// Checks the settings with the library's own checks; throws Usage_error with its message.
void check_settings(const Settings& settings, bool with_initialization);

/// Writes the settings as a JSON object named `key`; the automatic switches appear as chosen
/// ("auto" or the option's word) and as resolved for maps that are automatic (`automatic_input`)
/// or given.
void write_settings(Json_writer& json, const std::string& key, const Settings& settings, bool with_initialization,
                    bool automatic_input);

const char* oracle_name(smc::Distance_oracle_type t);

} // namespace comap

#endif // SMC_TOOLS_COMAP_SETTINGS_H
