// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later

#include "comap_settings.h"
#include "comap_parameters.h"

namespace comap {

const char* oracle_name(smc::Distance_oracle_type t)
{
  switch(t)
  {
  case smc::Distance_oracle_type::automatic: return "auto";
  case smc::Distance_oracle_type::dense: return "dense";
  case smc::Distance_oracle_type::local: return "local";
  }
  return "auto";
}

namespace {

/// An automatic switch (see Settings): "auto" -> -1, `off` -> 0, `on` -> 1.
int parse_automatic_switch(const std::string& option, const std::string& text, const char* off, const char* on)
{
  const int c = parse_choice(option, text, {off, on, "auto"});
  return c == 2 ? -1 : c;
}

/// The JSON value of an automatic switch: "auto" or the option's word for the choice.
std::string automatic_switch_text(int choice, const char* off, const char* on)
{
  return choice < 0 ? "auto" : choice == 1 ? on : off;
}

std::string fits_text(const std::vector<smc::internal::Fit_candidate>& fits)
{
  std::string s;
  for(std::size_t i = 0; i < fits.size(); ++i)
    s += (i ? "," : "") + std::to_string(fits[i].basis_size) + ":" + shortest(fits[i].orientation_weight) + ":" +
         shortest(fits[i].commutativity_weight);
  return s;
}

std::vector<smc::internal::Fit_candidate> parse_fits(const std::string& option, const std::string& text)
{
  std::vector<smc::internal::Fit_candidate> fits;
  for(const std::string& field : split(text, ','))
  {
    const std::vector<std::string> parts = split(field, ':');
    if(parts.size() != 3)
      throw Usage_error("bad value for " + option + ": \"" + field +
                        "\" (expected basis_size:orientation_weight:commutativity_weight)");
    fits.push_back({parse_int(option, parts[0]), parse_double(option, parts[1]), parse_double(option, parts[2])});
  }
  if(fits.empty()) throw Usage_error("bad value for " + option + ": empty list");
  return fits;
}

} // namespace

void add_algorithm_options(Option_parser& p, Settings& s, bool with_initialization)
{
  const Settings d;  // the library's defaults
  const smc::Refinement_settings automatic = smc::Refinement_settings::preset(smc::Refinement_preset::automatic_maps);
  smc::Refinement_settings& r = s.refinement;
  p.section("Coupled refinement (Algorithm 1)");
  p.value("--candidates", "M", "candidate target vertices per source vertex, m (without --candidates: " +
          std::to_string(automatic.number_of_candidates) + " for automatic initial maps)",
          std::to_string(d.refinement.number_of_candidates), [&r, &s](const std::string& v) {
            r.number_of_candidates = parse_int("--candidates", v, 1, 100000);
            s.number_of_candidates_given = true;
          });
  p.value("--rings", "R1,R2,...", "ring schedule: radius (in rings) of the candidate neighbourhoods at each outer "
          "iteration; the last one repeats (without --rings: " + join(automatic.ring_schedule) +
          " for automatic initial maps)",
          join(d.refinement.ring_schedule),
          [&r, &s](const std::string& v) {
            r.ring_schedule = parse_int_list("--rings", v);
            s.ring_schedule_given = true;
          });
  p.value("--mu", "X", "weight of the descriptor (unary) term against the geodesic (pairwise) term",
          shortest(d.refinement.unary_weight), [&r](const std::string& v) { r.unary_weight = parse_double("--mu", v); });
  p.value("--consistency-weight", "X", "weight of the cycle term: a candidate k of source vertex i costs X times the "
          "geodesic distance (relative to sqrt(area)) from i to the opposite map's match of k (0: the paper's energy; "
          "without --consistency-weight: " + shortest(automatic.consistency_weight) + " for automatic initial maps)",
          shortest(d.refinement.consistency_weight),
          [&r, &s](const std::string& v) {
            r.consistency_weight = parse_double("--consistency-weight", v);
            s.consistency_weight_given = true;
          });
  p.value("--outer-iterations", "N", "outer iterations (0: the length of the ring schedule)",
          std::to_string(d.refinement.number_of_outer_iterations),
          [&r](const std::string& v) { r.number_of_outer_iterations = parse_int("--outer-iterations", v, 0, 1000); });
  p.value("--coupling", "on|off", "candidates from the inverse of the opposite map too (off: the paper's "
          "non-coupled ablation)",
          on_off(d.refinement.use_coupling), [&r](const std::string& v) { r.use_coupling = parse_bool("--coupling", v); });
  p.flag("--no-coupling", "same as --coupling off", [&r] { r.use_coupling = false; });
  p.value("--propagation", "on|off", "also use the matches of the source neighbours as candidates",
          on_off(d.refinement.use_neighbor_matches),
          [&r](const std::string& v) { r.use_neighbor_matches = parse_bool("--propagation", v); });
  p.value("--pairwise-rings", "N", "pairwise terms between source vertices at most N rings apart (1: mesh edges)",
          std::to_string(d.refinement.pairwise_rings),
          [&r](const std::string& v) { r.pairwise_rings = parse_int("--pairwise-rings", v, 1, 10); });
  p.value("--stop-rule", "auto|consistency|none", "consistency: stop when the cycle-consistency error of Eq. (4) "
          "grows; none: run every outer iteration (the most consistent maps are returned either way); auto: "
          "consistency for automatic initial maps (their refined iterates become more consistent at each outer "
          "iteration with the cycle term), none for given ones",
          "auto", [&s](const std::string& v) { s.stop_rule = parse_automatic_switch("--stop-rule", v, "none", "consistency"); });
  p.value("--keep-input", "auto|on|off",
          "on: return the input maps unchanged when no refined iterate is more consistent (the paper's rule); "
          "off: return the most consistent refined iterate; auto: on for given initial maps, off for automatic "
          "ones (their lighter cycle term trades a little consistency for accuracy)",
          "auto", [&s](const std::string& v) {
            s.keep_consistent_input_maps = parse_automatic_switch("--keep-input", v, "off", "on");
          });
  p.value("--trws-iterations", "N", "TRW-S iterations per MRF solve (without --trws-iterations: " +
          std::to_string(automatic.trws_number_of_iterations) + " for automatic initial maps)",
          std::to_string(d.refinement.trws_number_of_iterations), [&r, &s](const std::string& v) {
            r.trws_number_of_iterations = parse_int("--trws-iterations", v, 1, 1000000);
            s.trws_number_of_iterations_given = true;
          });
  p.value("--trws-tolerance", "X", "TRW-S stops when the lower bound's relative change is below X",
          shortest(d.refinement.trws_relative_tolerance),
          [&r](const std::string& v) { r.trws_relative_tolerance = parse_double("--trws-tolerance", v); });

  smc::internal::Shape_settings& sh = s.shape;
  smc::Descriptor_settings& ds = sh.descriptors;
  p.section("Shape preparation (spectrum, descriptor stack, geodesic distances)");
  p.value("--eigenpairs", "K", "Laplace-Beltrami eigenpairs for HKS and WKS",
          std::to_string(d.shape.number_of_eigenpairs),
          [&sh](const std::string& v) { sh.number_of_eigenpairs = parse_int("--eigenpairs", v, 2, 100000); });
  p.value("--intrinsic-delaunay", "on|off", "build the Laplacian on the intrinsic Delaunay triangulation",
          on_off(d.shape.use_intrinsic_delaunay),
          [&sh](const std::string& v) { sh.use_intrinsic_delaunay = parse_bool("--intrinsic-delaunay", v); });
  p.value("--hks-weight", "W", "weight of the heat kernel signature in the descriptor stack (0: none)",
          shortest(d.shape.descriptors.hks_weight),
          [&ds](const std::string& v) { ds.hks_weight = parse_double("--hks-weight", v); });
  p.value("--wks-weight", "W", "weight of the wave kernel signature (0: none)", shortest(d.shape.descriptors.wks_weight),
          [&ds](const std::string& v) { ds.wks_weight = parse_double("--wks-weight", v); });
  p.value("--shot-weight", "W", "weight of SHOT (0: none)", shortest(d.shape.descriptors.shot_weight),
          [&ds](const std::string& v) { ds.shot_weight = parse_double("--shot-weight", v); });
  p.value("--hks-scales", "N", "HKS time scales", std::to_string(d.shape.descriptors.number_of_hks_scales),
          [&ds](const std::string& v) { ds.number_of_hks_scales = parse_int("--hks-scales", v, 1, 100000); });
  p.value("--wks-energies", "N", "WKS energies", std::to_string(d.shape.descriptors.number_of_wks_energies),
          [&ds](const std::string& v) { ds.number_of_wks_energies = parse_int("--wks-energies", v, 1, 100000); });
  p.value("--wks-variance", "X", "WKS filter width, in energy steps", shortest(d.shape.descriptors.wks_variance),
          [&ds](const std::string& v) { ds.wks_variance = parse_double("--wks-variance", v); });
  p.value("--shot-radius", "X", "SHOT support radius, relative to sqrt(area)", shortest(d.shape.descriptors.shot_radius),
          [&ds](const std::string& v) { ds.shot_radius = parse_double("--shot-radius", v); });
  p.value("--oracle", "auto|dense|local", "geodesic distance oracle: dense all-pairs matrix (n^2 memory) or local "
          "exact distances with a landmark estimate beyond",
          oracle_name(d.shape.oracle), [&sh](const std::string& v) {
            const smc::Distance_oracle_type types[3] = {smc::Distance_oracle_type::automatic,
                                                        smc::Distance_oracle_type::dense,
                                                        smc::Distance_oracle_type::local};
            sh.oracle = types[parse_choice("--oracle", v, {"auto", "dense", "local"})];
          });
  p.value("--oracle-radius", "X", "radius of the local oracle's exact distances, in mean edge lengths",
          shortest(d.shape.local_radius_in_edge_lengths),
          [&sh](const std::string& v) { sh.local_radius_in_edge_lengths = parse_double("--oracle-radius", v); });
  p.value("--oracle-landmarks", "N", "landmarks of the local oracle's far-distance estimate",
          std::to_string(d.shape.number_of_landmarks),
          [&sh](const std::string& v) { sh.number_of_landmarks = parse_int("--oracle-landmarks", v, 1, 100000); });

  if(!with_initialization) return;
  smc::internal::Initialization_settings& in = s.initialization;
  const smc::internal::Initialization_settings& di = d.initialization;
  p.section("Automatic initialisation (functional maps + ZoomOut; used without initial maps)");
  p.value("--init-fits", "K:WO:WC,...", "functional map fits tried (basis size : orientation weight : "
          "commutativity weight); the best after a short ZoomOut is kept",
          fits_text(di.candidates), [&in](const std::string& v) { in.candidates = parse_fits("--init-fits", v); });
  p.value("--init-selection-size", "K", "basis size at which the fits are compared", std::to_string(di.selection_size),
          [&in](const std::string& v) { in.selection_size = parse_int("--init-selection-size", v, 2, 100000); });
  p.value("--init-select-by", "distortion|descriptors",
          "how the fits are compared: geodesic distortion of the sample maps, or descriptor distance",
          di.select_by_distortion ? "distortion" : "descriptors", [&in](const std::string& v) {
            if(v != "distortion" && v != "descriptors")
              throw Usage_error("bad value for --init-select-by: \"" + v + "\" (expected distortion or descriptors)");
            in.select_by_distortion = v == "distortion";
          });
  p.value("--init-distortion-samples", "N", "samples whose pairwise geodesic distances score the fits",
          std::to_string(di.distortion_samples),
          [&in](const std::string& v) { in.distortion_samples = parse_int("--init-distortion-samples", v, 2, 100000); });
  p.value("--init-basis", "K", "final ZoomOut basis size (the shapes need more vertices than this)",
          std::to_string(di.zoomout_final_size),
          [&in](const std::string& v) { in.zoomout_final_size = parse_int("--init-basis", v, 2, 100000); });
  p.value("--init-pass-basis", "K", "basis size at which each pass (first and repair passes) ends its ZoomOut; the "
          "kept maps then grow to --init-basis",
          std::to_string(di.zoomout_pass_size),
          [&in](const std::string& v) { in.zoomout_pass_size = parse_int("--init-pass-basis", v, 2, 100000); });
  p.value("--init-step", "N", "ZoomOut basis growth per iteration", std::to_string(di.zoomout_step),
          [&in](const std::string& v) { in.zoomout_step = parse_int("--init-step", v, 1, 100000); });
  p.value("--init-growth-step", "N", "ZoomOut basis growth per iteration from --init-pass-basis to --init-basis",
          std::to_string(di.zoomout_growth_step),
          [&in](const std::string& v) { in.zoomout_growth_step = parse_int("--init-growth-step", v, 1, 100000); });
  p.value("--init-eigenpairs", "K", "eigenpairs for the initialisation (0: the final basis size)",
          std::to_string(di.number_of_eigenpairs),
          [&in](const std::string& v) { in.number_of_eigenpairs = parse_int("--init-eigenpairs", v, 0, 100000); });
  p.value("--init-wks-weight", "W", "weight of the WKS columns", shortest(di.wks_weight),
          [&in](const std::string& v) { in.wks_weight = parse_double("--init-wks-weight", v); });
  p.value("--init-hks-weight", "W", "weight of the HKS columns", shortest(di.hks_weight),
          [&in](const std::string& v) { in.hks_weight = parse_double("--init-hks-weight", v); });
  p.value("--init-wks-energies", "N", "WKS energies", std::to_string(di.number_of_wks_energies),
          [&in](const std::string& v) { in.number_of_wks_energies = parse_int("--init-wks-energies", v, 1, 100000); });
  p.value("--init-wks-variance", "X", "WKS filter width, in energy steps", shortest(di.wks_variance),
          [&in](const std::string& v) { in.wks_variance = parse_double("--init-wks-variance", v); });
  p.value("--init-hks-scales", "N", "HKS time scales", std::to_string(di.number_of_hks_scales),
          [&in](const std::string& v) { in.number_of_hks_scales = parse_int("--init-hks-scales", v, 1, 100000); });
  p.value("--init-signed-weight", "W", "weight of the orientation-sensitive descriptors (0: none)",
          shortest(di.signed_descriptor_weight),
          [&in](const std::string& v) { in.signed_descriptor_weight = parse_double("--init-signed-weight", v); });
  p.value("--init-signed-smoothing", "K", "eigenfunctions that smooth the orientation-sensitive descriptors",
          std::to_string(di.signed_descriptor_smoothing), [&in](const std::string& v) {
            in.signed_descriptor_smoothing = parse_int("--init-signed-smoothing", v, 0, 100000);
          });
  p.value("--init-operators", "N", "descriptors with multiplication and orientation operators",
          std::to_string(di.number_of_operator_descriptors), [&in](const std::string& v) {
            in.number_of_operator_descriptors = parse_int("--init-operators", v, 0, 100000);
          });
  p.value("--init-procrustes", "on|off", "replace each fitted functional map by the nearest orthogonal one",
          on_off(di.procrustes), [&in](const std::string& v) { in.procrustes = parse_bool("--init-procrustes", v); });
  p.value("--init-coupled-zoomout", "on|off", "grow both maps jointly (favours inverse pairs)",
          on_off(di.coupled_zoomout),
          [&in](const std::string& v) { in.coupled_zoomout = parse_bool("--init-coupled-zoomout", v); });
  p.value("--init-bijectivity", "W", "weight of the bijectivity term of the coupled ZoomOut",
          shortest(di.zoomout_bijectivity_weight),
          [&in](const std::string& v) { in.zoomout_bijectivity_weight = parse_double("--init-bijectivity", v); });
  p.value("--init-samples", "N", "vertices sampled per ZoomOut iteration (0: all)",
          std::to_string(di.zoomout_number_of_samples),
          [&in](const std::string& v) { in.zoomout_number_of_samples = parse_int("--init-samples", v, 0, 100000000); });
  p.value("--init-repair-passes", "N", "tear repair passes at most: maps whose tears cut off part of a mesh are "
          "recomputed with landmarks from their core (0: no repair)",
          std::to_string(di.tear_repair_passes),
          [&in](const std::string& v) { in.tear_repair_passes = parse_int("--init-repair-passes", v, 0, 100); });
  p.value("--init-distortion-repair", "N", "distortion repair passes at most: the maps are recomputed with "
          "landmarks from their isometric core (the samples whose geodesic distances they preserve) and kept when "
          "they distort distances less (0: none)",
          std::to_string(di.distortion_repair_passes),
          [&in](const std::string& v) { in.distortion_repair_passes = parse_int("--init-distortion-repair", v, 0, 100); });
  p.value("--compare-automatic-above", "X", "with --compare-automatic: compute and compare the automatic maps "
          "only when the given maps' sample distortion (after the repair with --repair) is above X (0: always)",
          shortest(di.automatic_maps_comparison_threshold),
          [&in, &s](const std::string& v) {
            in.automatic_maps_comparison_threshold = parse_double("--compare-automatic-above", v);
            s.comparison_threshold_given = true;
          });
  p.value("--init-tear-threshold", "X", "a source edge is torn when its images are this far apart (relative to "
          "sqrt(area) of the target)",
          shortest(di.tear_threshold),
          [&in](const std::string& v) { in.tear_threshold = parse_double("--init-tear-threshold", v); });
  p.value("--init-tear-fraction", "X", "repair when the tears cut off more than this area fraction of a mesh",
          shortest(di.tear_min_fraction),
          [&in](const std::string& v) { in.tear_min_fraction = parse_double("--init-tear-fraction", v); });
  p.value("--init-repair-distortion", "X", "a tear repair pass is kept only when its maps distort the geodesic "
          "distances of the distortion samples at most this fraction more than the maps they replace (negative: no "
          "check)",
          shortest(di.tear_repair_distortion_tolerance), [&in](const std::string& v) {
            in.tear_repair_distortion_tolerance = parse_double("--init-repair-distortion", v);
          });
  p.value("--init-repair-landmarks", "N", "landmarks sampled in the core of each map by a repair pass",
          std::to_string(di.tear_repair_landmarks),
          [&in](const std::string& v) { in.tear_repair_landmarks = parse_int("--init-repair-landmarks", v, 1, 100000); });
}

void check_settings(const Settings& s, bool with_initialization)
{
  // --compare-automatic sets compare_with_automatic_maps, in match and bench alike.
  if(s.comparison_threshold_given && !s.initialization.compare_with_automatic_maps)
    throw Usage_error("--compare-automatic-above needs --compare-automatic");
  try
  {
    s.refinement.check();
    s.shape.descriptors.check();
    // The library reads the shape settings back from named parameters and checks them there.
    smc::internal::Shape_settings::from(shape_parameters(s.shape, s.shape.number_of_eigenpairs));
    if(with_initialization) smc::internal::check_initialization_settings(s.initialization);
  }
  catch(const smc::Error& e)
  {
    throw Usage_error(std::string("bad parameter: ") + e.what());
  }
}

smc::Refinement_settings resolved_refinement(const Settings& settings, bool automatic_input)
{
  const smc::Refinement_settings preset = smc::Refinement_settings::preset(
      automatic_input ? smc::Refinement_preset::automatic_maps : smc::Refinement_preset::given_maps);
  smc::Refinement_settings r = settings.refinement;
  r.keep_consistent_input_maps = resolve_switch(settings.keep_consistent_input_maps, preset.keep_consistent_input_maps);
  r.stop_when_consistency_worsens = resolve_switch(settings.stop_rule, preset.stop_when_consistency_worsens);
  if(!settings.ring_schedule_given) r.ring_schedule = preset.ring_schedule;
  if(!settings.consistency_weight_given) r.consistency_weight = preset.consistency_weight;
  if(!settings.number_of_candidates_given) r.number_of_candidates = preset.number_of_candidates;
  if(!settings.trws_number_of_iterations_given) r.trws_number_of_iterations = preset.trws_number_of_iterations;
  return r;
}

void write_settings(Json_writer& json, const std::string& key, const Settings& s, bool with_initialization,
                    bool automatic_input)
{
  json.begin_object(key);
  const smc::Refinement_settings r = resolved_refinement(s, automatic_input);
  json.begin_object("refinement")
      .value("number_of_candidates", r.number_of_candidates)
      .value("ring_schedule", r.ring_schedule)
      .value("unary_weight", r.unary_weight)
      .value("consistency_weight", r.consistency_weight)
      .value("number_of_outer_iterations", r.outer_iterations())
      .value("use_coupling", r.use_coupling)
      .value("use_neighbor_matches", r.use_neighbor_matches)
      .value("pairwise_rings", r.pairwise_rings)
      .value("stop_rule", automatic_switch_text(s.stop_rule, "none", "consistency"))
      .value("stop_when_consistency_worsens", r.stop_when_consistency_worsens)
      .value("keep_input", automatic_switch_text(s.keep_consistent_input_maps, "off", "on"))
      .value("keep_consistent_input_maps", r.keep_consistent_input_maps)
      .value("trws_number_of_iterations", r.trws_number_of_iterations)
      .value("trws_relative_tolerance", r.trws_relative_tolerance)
      .end_object();
  const smc::Descriptor_settings& d = s.shape.descriptors;
  json.begin_object("shape")
      .value("number_of_eigenpairs", s.shape.number_of_eigenpairs)
      .value("use_intrinsic_delaunay", s.shape.use_intrinsic_delaunay)
      .value("hks_weight", d.hks_weight)
      .value("wks_weight", d.wks_weight)
      .value("shot_weight", d.shot_weight)
      .value("number_of_hks_scales", d.number_of_hks_scales)
      .value("number_of_wks_energies", d.number_of_wks_energies)
      .value("wks_variance", d.wks_variance)
      .value("shot_radius", d.shot_radius)
      .value("distance_oracle", oracle_name(s.shape.oracle))
      .value("oracle_radius_in_edge_lengths", s.shape.local_radius_in_edge_lengths)
      .value("oracle_landmarks", s.shape.number_of_landmarks)
      .end_object();
  if(with_initialization)
  {
    const smc::internal::Initialization_settings& in = s.initialization;
    json.begin_object("initialization");
    json.begin_array("fits");
    for(const auto& f : in.candidates)
      json.begin_object()
          .value("basis_size", f.basis_size)
          .value("orientation_weight", f.orientation_weight)
          .value("commutativity_weight", f.commutativity_weight)
          .end_object();
    json.end_array();
    json.value("selection_size", in.selection_size)
        .value("zoomout_final_size", in.zoomout_final_size)
        .value("zoomout_pass_size", in.zoomout_pass_size)
        .value("zoomout_step", in.zoomout_step)
        .value("zoomout_growth_step", in.zoomout_growth_step)
        .value("number_of_eigenpairs", smc::internal::initialization_number_of_eigenpairs(in))
        .value("wks_weight", in.wks_weight)
        .value("hks_weight", in.hks_weight)
        .value("number_of_wks_energies", in.number_of_wks_energies)
        .value("wks_variance", in.wks_variance)
        .value("number_of_hks_scales", in.number_of_hks_scales)
        .value("signed_descriptor_weight", in.signed_descriptor_weight)
        .value("signed_descriptor_smoothing", in.signed_descriptor_smoothing)
        .value("number_of_operator_descriptors", in.number_of_operator_descriptors)
        .value("procrustes", in.procrustes)
        .value("coupled_zoomout", in.coupled_zoomout)
        .value("zoomout_bijectivity_weight", in.zoomout_bijectivity_weight)
        .value("zoomout_number_of_samples", in.zoomout_number_of_samples)
        .value("tear_repair_passes", in.tear_repair_passes)
        .value("tear_repair_distortion_tolerance", in.tear_repair_distortion_tolerance)
        .value("distortion_repair_passes", in.distortion_repair_passes)
        .value("compare_with_automatic_maps", in.compare_with_automatic_maps)
        .value("automatic_maps_comparison_threshold", in.automatic_maps_comparison_threshold)
        .end_object();
  }
  json.end_object();
}

} // namespace comap
