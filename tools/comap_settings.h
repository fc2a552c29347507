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
  /// The refinement's defaults depend on the initial maps: smc::Refinement_preset::given_maps
  /// for maps read from files, smc::Refinement_preset::automatic_maps for automatic ones (see
  /// resolved_refinement()). The switches below are -1 (automatic: the preset's choice) unless
  /// their option was given; the flags record which of the other options that differ between the
  /// presets were given (those apply to every kind of maps).
  /// Refinement_settings::keep_consistent_input_maps: 1 on (the paper's rule), 0 off, -1 automatic.
  int keep_consistent_input_maps = -1;
  /// Refinement_settings::stop_when_consistency_worsens: 1 consistency (the paper's Eq. (4) early
  /// stop), 0 none (run the whole ring schedule), -1 automatic. On given maps the whole schedule
  /// is better: their later iterates become the most consistent (TOSCA_r WKS maps: 0.0454 against
  /// 0.0460).
  int stop_rule = -1;
  bool ring_schedule_given = false;              ///< --rings was given
  bool number_of_candidates_given = false;       ///< --candidates was given
  bool trws_number_of_iterations_given = false;  ///< --trws-iterations was given
  bool consistency_weight_given = false;         ///< --consistency-weight was given
  bool comparison_threshold_given = false;       ///< --compare-automatic-above was given
};

/// The value of an automatic switch of Settings (1 on, 0 off, -1 automatic): `preset_value` when
/// the switch is automatic.
inline bool resolve_switch(int choice, bool preset_value) { return choice < 0 ? preset_value : choice == 1; }

/// The refinement settings for initial maps that are automatic or given: the options given, and
/// the values of the matching smc::Refinement_preset for the options of Settings that were not
/// (keep-input, stop rule, ring schedule, candidates, TRW-S iterations, cycle term weight).
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
