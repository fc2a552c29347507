// Copyright (c) 2026 The Surface_mesh_correspondence developers.
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Every tunable setting of the matching pipeline in one struct, generated from the registry
// (internal/settings_list.h): its defaults, the reader of the named parameters, the range checks,
// and the access by name that settings files and language bindings use.

#ifndef CGAL_SURFACE_MESH_CORRESPONDENCE_MATCHING_SETTINGS_H
#define CGAL_SURFACE_MESH_CORRESPONDENCE_MATCHING_SETTINGS_H

#include <CGAL/Surface_mesh_correspondence/exceptions.h>
#include <CGAL/Surface_mesh_correspondence/internal/settings_list.h>
#include <CGAL/Surface_mesh_correspondence/parameters.h>

#include <algorithm>
#include <bitset>
#include <cmath>
#include <cstddef>
#include <limits>
#include <sstream>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

namespace CGAL {
namespace Surface_mesh_correspondence {

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// The stages of match_shapes(), in the order they run (see Default_matching_visitor). Each
/// setting of the registry is read by one of them.
enum class Matching_stage
{
  validation,      ///< the meshes, maps and settings are checked
  preparation,     ///< spectra, descriptors and geodesic distances of each shape
  initialization,  ///< the automatic initial maps (functional maps and ZoomOut, tear repair)
  repair,          ///< given maps: the repair of their tears
  comparison,      ///< given maps: the comparison with the automatic maps
  refinement,      ///< the coupled refinement (Azencot, Dubrovina and Guibas 2019)
  selection        ///< where the refined maps replace their input
};

/// \ingroup PkgSurfaceMeshCorrespondenceRef
inline const char* to_string(Matching_stage s)
{
  switch(s)
  {
  case Matching_stage::validation: return "validation";
  case Matching_stage::preparation: return "preparation";
  case Matching_stage::initialization: return "initialization";
  case Matching_stage::repair: return "repair";
  case Matching_stage::comparison: return "comparison";
  case Matching_stage::refinement: return "refinement";
  case Matching_stage::selection: return "selection";
  }
  return "unknown";
}

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Which geodesic distance oracle a shape uses for the pairwise terms of the coupled refinement
/// (setting `distance_oracle`).
enum class Distance_oracle_type
{
  automatic,  ///< the local oracle
  dense,      ///< all pairs in a float matrix (Dense_distance_oracle): n^2 memory
  local       ///< exact within a radius, landmark estimate beyond (Local_distance_oracle): linear memory
};

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Where match_shapes() lets the refined maps replace their input (setting `refinement_selection`).
enum class Refinement_selection
{
  /// Everywhere when the refined maps are more consistent than their input (Eq. 4 of the paper);
  /// else only in the regions where they distort mid-range geodesic distances less.
  regions,
  /// The refined maps whole when they are more consistent than their input, else the input
  /// (the paper's rule).
  consistency,
  /// Always the refined maps.
  refined
};

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// One functional map fit tried by the automatic initialisation (setting `initialization_fits`).
struct Functional_map_fit
{
  int basis_size;               ///< k0: size of the fitted functional map
  double orientation_weight;    ///< w_o: weight of the orientation operators
  double commutativity_weight;  ///< w_c: weight of the descriptor multiplication operators
};

inline bool operator==(const Functional_map_fit& a, const Functional_map_fit& b)
{
  return a.basis_size == b.basis_size && a.orientation_weight == b.orientation_weight &&
         a.commutativity_weight == b.commutativity_weight;
}

/// A list of integers (setting `ring_schedule`).
typedef std::vector<int> Int_list;
/// A list of fits (setting `initialization_fits`).
typedef std::vector<Functional_map_fit> Fit_list;

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// Where the maps that match_shapes() refines came from: their kind decides the defaults of six
/// refinement settings (the registry's "default for given maps").
enum class Map_origin
{
  automatic,  ///< computed by the automatic initialisation (or a repair pass of it)
  given       ///< given by the caller and kept by the repair and the comparison
};

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// A valid range of a numeric setting (of each element of a list).
struct Setting_range
{
  double minimum = -std::numeric_limits<double>::infinity();
  double maximum = std::numeric_limits<double>::infinity();
  bool open_minimum = false, open_maximum = false;

  bool contains(double x) const
  {
    // Infinite bounds are open: no setting takes an infinite (or NaN) value.
    return std::isfinite(x) && (open_minimum ? x > minimum : x >= minimum) &&
           (open_maximum ? x < maximum : x <= maximum);
  }
  /// "[0, inf)", "(0, inf)", "[1, 100000]"
  std::string text() const
  {
    auto number = [](double x) {
      if(std::isinf(x)) return std::string(x > 0 ? "inf" : "-inf");
      std::ostringstream s;
      s << x;
      return s.str();
    };
    return std::string(open_minimum || std::isinf(minimum) ? "(" : "[") + number(minimum) + ", " + number(maximum) +
           (open_maximum || std::isinf(maximum) ? ")" : "]");
  }
};

namespace internal {

inline Setting_range range_any() { return Setting_range(); }
inline Setting_range range_at_least(double a) { Setting_range r; r.minimum = a; return r; }
inline Setting_range range_above(double a) { Setting_range r; r.minimum = a; r.open_minimum = true; return r; }
inline Setting_range range_between(double a, double b) { Setting_range r; r.minimum = a; r.maximum = b; return r; }

/// Identifiers of the settings, in registry order.
enum Setting_id
{
#define CGAL_SMC_SETTING_ID(NAME, TYPE, DEFAULT, GIVEN_DEFAULT, RANGE, STAGE, DOC) NAME##_id,
  CGAL_SMC_SETTINGS(CGAL_SMC_SETTING_ID)
#undef CGAL_SMC_SETTING_ID
  number_of_settings
};

} // namespace internal

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// A setting's value as settings files and language bindings give it: a Boolean, a number, a
/// word (enumerations), a list of numbers (`ring_schedule`) or a list of lists of numbers
/// (`initialization_fits`: [basis size, orientation weight, commutativity weight] each).
typedef std::variant<bool, double, std::string, std::vector<double>, std::vector<std::vector<double> > >
    Setting_value;

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// What the registry says of one setting (matching_settings_registry()).
struct Setting_info
{
  std::string name;
  std::string type;                ///< "int", "double", "bool", "int list", "fit list" or "word"
  std::string default_text;        ///< the default, as a settings file writes it
  std::string given_default_text;  ///< the default when the refined maps were given
  std::string range_text;          ///< "[1, 100000]", or the valid words
  Matching_stage stage;
  std::string documentation;       ///< one line
};

namespace internal {

/// How each type of setting is checked, written and read.
template <typename T>
struct Setting_traits;

template <>
struct Setting_traits<double>
{
  static const char* type_name() { return "double"; }
  static bool in_range(double v, const Setting_range& r) { return r.contains(v); }
  static std::string text(double v)
  {
    if(v == std::floor(v) && std::abs(v) < 1e15) return std::to_string(static_cast<long long>(v));
    std::ostringstream s;
    s.precision(17);
    s << v;
    std::string shortest = s.str();
    for(int p = 1; p < 17; ++p)
    {
      std::ostringstream t;
      t.precision(p);
      t << v;
      if(std::stod(t.str()) == v) return t.str();
    }
    return shortest;
  }
  static double from(const Setting_value& v, const std::string& name)
  {
    if(const double* x = std::get_if<double>(&v)) return *x;
    throw Invalid_parameter_error(name + " must be a number");
  }
};

template <>
struct Setting_traits<int>
{
  static const char* type_name() { return "int"; }
  static bool in_range(int v, const Setting_range& r) { return r.contains(double(v)); }
  static std::string text(int v) { return std::to_string(v); }
  static int from_number(double x, const std::string& name)
  {
    if(!(std::abs(x) < 2e9) || x != std::floor(x))
      throw Invalid_parameter_error(name + " must be an integer (not " + Setting_traits<double>::text(x) + ")");
    return static_cast<int>(x);
  }
  static int from(const Setting_value& v, const std::string& name)
  {
    if(const double* x = std::get_if<double>(&v)) return from_number(*x, name);
    throw Invalid_parameter_error(name + " must be an integer");
  }
};

template <>
struct Setting_traits<bool>
{
  static const char* type_name() { return "bool"; }
  static bool in_range(bool, const Setting_range&) { return true; }
  static std::string text(bool v) { return v ? "true" : "false"; }
  static bool from(const Setting_value& v, const std::string& name)
  {
    if(const bool* b = std::get_if<bool>(&v)) return *b;
    throw Invalid_parameter_error(name + " must be true or false");
  }
};

template <>
struct Setting_traits<Int_list>
{
  static const char* type_name() { return "int list"; }
  static bool in_range(const Int_list& v, const Setting_range& r)
  {
    return !v.empty() && std::all_of(v.begin(), v.end(), [&](int x) { return r.contains(double(x)); });
  }
  static std::string text(const Int_list& v)
  {
    std::string s = "[";
    for(std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + std::to_string(v[i]);
    return s + "]";
  }
  static Int_list from(const Setting_value& v, const std::string& name)
  {
    const std::vector<double>* x = std::get_if<std::vector<double> >(&v);
    if(!x) throw Invalid_parameter_error(name + " must be a list of integers");
    Int_list out;
    for(double e : *x) out.push_back(Setting_traits<int>::from_number(e, name));
    return out;
  }
};

template <>
struct Setting_traits<Fit_list>
{
  static const char* type_name() { return "fit list"; }
  static bool in_range(const Fit_list& v, const Setting_range&)
  {
    return !v.empty() && std::all_of(v.begin(), v.end(), [](const Functional_map_fit& f) {
             return f.basis_size >= 2 && f.orientation_weight >= 0 && f.commutativity_weight >= 0 &&
                    std::isfinite(f.orientation_weight) && std::isfinite(f.commutativity_weight);
           });
  }
  static std::string text(const Fit_list& v)
  {
    std::string s = "[";
    for(std::size_t i = 0; i < v.size(); ++i)
      s += std::string(i ? ", " : "") + "[" + std::to_string(v[i].basis_size) + ", " +
           Setting_traits<double>::text(v[i].orientation_weight) + ", " +
           Setting_traits<double>::text(v[i].commutativity_weight) + "]";
    return s + "]";
  }
  static Fit_list from(const Setting_value& v, const std::string& name)
  {
    const std::vector<std::vector<double> >* x = std::get_if<std::vector<std::vector<double> > >(&v);
    if(!x)
      throw Invalid_parameter_error(name +
                                    " must be a list of [basis size, orientation weight, commutativity weight]");
    Fit_list out;
    for(const std::vector<double>& f : *x)
    {
      if(f.size() != 3)
        throw Invalid_parameter_error(name + ": each fit is [basis size, orientation weight, commutativity weight]");
      out.push_back({Setting_traits<int>::from_number(f[0], name), f[1], f[2]});
    }
    return out;
  }
};

/// Enumerations are written as words.
template <typename Enum>
struct Enum_setting_traits
{
  static const char* type_name() { return "word"; }
  static bool in_range(Enum, const Setting_range&) { return true; }
  static std::string text(Enum v) { return Setting_traits<Enum>::words()[static_cast<std::size_t>(v)]; }
  static std::string all_words()
  {
    const std::vector<std::string> all = Setting_traits<Enum>::words();
    std::string s;
    for(std::size_t i = 0; i < all.size(); ++i) s += (i == 0 ? "" : i + 1 == all.size() ? " or " : ", ") + all[i];
    return s;
  }
  static Enum from(const Setting_value& v, const std::string& name)
  {
    if(const std::string* w = std::get_if<std::string>(&v))
    {
      const std::vector<std::string> all = Setting_traits<Enum>::words();
      for(std::size_t i = 0; i < all.size(); ++i)
        if(*w == all[i]) return static_cast<Enum>(i);
    }
    throw Invalid_parameter_error(name + " must be " + all_words());
  }
};

template <>
struct Setting_traits<Distance_oracle_type> : Enum_setting_traits<Distance_oracle_type>
{
  static std::vector<std::string> words() { return {"automatic", "dense", "local"}; }
};

template <>
struct Setting_traits<Refinement_selection> : Enum_setting_traits<Refinement_selection>
{
  static std::vector<std::string> words() { return {"regions", "consistency", "refined"}; }
};

template <typename T>
std::string range_text(const Setting_range& r)
{
  if constexpr(std::is_same<T, bool>::value) return "true or false";
  else if constexpr(std::is_enum<T>::value) return Setting_traits<T>::all_words();
  else if constexpr(std::is_same<T, Fit_list>::value) return "basis size >= 2, weights >= 0";
  else return r.text();
}

/// The edit distance between two names (for "did you mean" messages).
inline std::size_t edit_distance(const std::string& a, const std::string& b)
{
  std::vector<std::size_t> row(b.size() + 1);
  for(std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for(std::size_t i = 1; i <= a.size(); ++i)
  {
    std::size_t diagonal = row[0];
    row[0] = i;
    for(std::size_t j = 1; j <= b.size(); ++j)
    {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

} // namespace internal

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// The value of every setting of the registry (one member per setting, named as the setting and
/// initialised to its default), and which of them were set. match_shapes() and the component
/// functions read their named parameters into this struct (from()); settings files and language
/// bindings set its members by name (set()). Six refinement settings default to other values when
/// the maps to refine were given by the caller (resolved()).
struct Matching_settings
{
#define CGAL_SMC_SETTING_MEMBER(NAME, TYPE, DEFAULT, GIVEN_DEFAULT, RANGE, STAGE, DOC) TYPE NAME = DEFAULT;
  CGAL_SMC_SETTINGS(CGAL_SMC_SETTING_MEMBER)
#undef CGAL_SMC_SETTING_MEMBER

  /// Whether the setting `name` was set (by a named parameter or set()).
  bool is_set(const std::string& name) const { return given_[index_of(name)]; }

  /// The settings read from named parameters: those of `matching_settings` when given, then each
  /// setting given by its own named parameter. Checks every value (check()).
  template <typename NamedParameters>
  static Matching_settings from(const NamedParameters& np)
  {
    Matching_settings s;
    const auto& base = parameters::get_parameter_reference(np, internal_np::matching_settings);
    if constexpr(!std::is_same<typename std::decay<decltype(base)>::type,
                               CGAL::internal_np::Param_not_found>::value)
    {
      const Matching_settings& b = base;
      s = b;
    }
#define CGAL_SMC_SETTING_READ(NAME, TYPE, DEFAULT, GIVEN_DEFAULT, RANGE, STAGE, DOC)                                   \
  if constexpr(!parameters::is_default_parameter<NamedParameters, internal_np::NAME##_t>::value)               \
  {                                                                                                            \
    s.NAME = parameters::choose_parameter(parameters::get_parameter(np, internal_np::NAME), s.NAME);           \
    s.given_.set(internal::NAME##_id);                                                                         \
  }
    CGAL_SMC_SETTINGS(CGAL_SMC_SETTING_READ)
#undef CGAL_SMC_SETTING_READ
    s.check();
    return s;
  }

  /// Throws Invalid_parameter_error naming the first setting outside its range, and the range.
  void check() const
  {
    using namespace internal;
#define CGAL_SMC_SETTING_CHECK(NAME, TYPE, DEFAULT, GIVEN_DEFAULT, RANGE, STAGE, DOC)                                  \
  if(!Setting_traits<TYPE>::in_range(NAME, RANGE))                                                             \
    throw Invalid_parameter_error(std::string(#NAME " = ") + Setting_traits<TYPE>::text(NAME) +                \
                                  " is out of its range " + range_text<TYPE>(RANGE));
    CGAL_SMC_SETTINGS(CGAL_SMC_SETTING_CHECK)
#undef CGAL_SMC_SETTING_CHECK
  }

  /// Sets the setting `name` to `value` (checked against its type and range). An unknown name
  /// throws Invalid_parameter_error naming the closest valid one.
  void set(const std::string& name, const Setting_value& value)
  {
    using namespace internal;
    const std::size_t id = index_of(name);
    switch(id)
    {
#define CGAL_SMC_SETTING_SET(NAME, TYPE, DEFAULT, GIVEN_DEFAULT, RANGE, STAGE, DOC)                                    \
  case NAME##_id:                                                                                              \
  {                                                                                                            \
    const TYPE v = Setting_traits<TYPE>::from(value, #NAME);                                                   \
    if(!Setting_traits<TYPE>::in_range(v, RANGE))                                                              \
      throw Invalid_parameter_error(std::string(#NAME " = ") + Setting_traits<TYPE>::text(v) +                 \
                                    " is out of its range " + range_text<TYPE>(RANGE));                        \
    this->NAME = v;                                                                                            \
    break;                                                                                                     \
  }
      CGAL_SMC_SETTINGS(CGAL_SMC_SETTING_SET)
#undef CGAL_SMC_SETTING_SET
    default: break;
    }
    given_.set(id);
  }

  /// The value of the setting `name` as a settings file writes it ("40", "[4, 3, 2, 1]", "true").
  std::string text(const std::string& name) const
  {
    using namespace internal;
    switch(index_of(name))
    {
#define CGAL_SMC_SETTING_TEXT(NAME, TYPE, DEFAULT, GIVEN_DEFAULT, RANGE, STAGE, DOC)                                   \
  case NAME##_id: return Setting_traits<TYPE>::text(this->NAME);
      CGAL_SMC_SETTINGS(CGAL_SMC_SETTING_TEXT)
#undef CGAL_SMC_SETTING_TEXT
    default: return std::string();
    }
  }

  /// These settings with the defaults of maps of origin `origin` for the settings that were not
  /// set (the registry's "default for given maps" when `origin` is Map_origin::given).
  Matching_settings resolved(Map_origin origin) const
  {
    Matching_settings s = *this;
    if(origin == Map_origin::given)
    {
#define CGAL_SMC_SETTING_RESOLVE(NAME, TYPE, DEFAULT, GIVEN_DEFAULT, RANGE, STAGE, DOC)                                \
  if(!given_[internal::NAME##_id]) s.NAME = GIVEN_DEFAULT;
      CGAL_SMC_SETTINGS(CGAL_SMC_SETTING_RESOLVE)
#undef CGAL_SMC_SETTING_RESOLVE
    }
    return s;
  }

  /// The index of `name` in the registry; throws Invalid_parameter_error for an unknown name,
  /// naming the closest valid one.
  static std::size_t index_of(const std::string& name)
  {
    static const char* const names[] = {
#define CGAL_SMC_SETTING_NAME(NAME, TYPE, DEFAULT, GIVEN_DEFAULT, RANGE, STAGE, DOC) #NAME,
        CGAL_SMC_SETTINGS(CGAL_SMC_SETTING_NAME)
#undef CGAL_SMC_SETTING_NAME
    };
    std::size_t best = 0, best_distance = std::string::npos;
    for(std::size_t i = 0; i < internal::number_of_settings; ++i)
    {
      if(name == names[i]) return i;
      const std::size_t d = internal::edit_distance(name, names[i]);
      if(d < best_distance)
      {
        best = i;
        best_distance = d;
      }
    }
    throw Invalid_parameter_error("unknown setting \"" + name + "\" (did you mean \"" + names[best] + "\"?)");
  }

private:
  std::bitset<internal::number_of_settings> given_;
};

namespace internal {

/// The registry's defaults (a default-constructed Matching_settings).
inline const Matching_settings& matching_defaults()
{
  static const Matching_settings defaults;
  return defaults;
}

} // namespace internal

/// \ingroup PkgSurfaceMeshCorrespondenceRef
/// The registry: every setting with its type, defaults, valid range, stage and documentation, in
/// registry order.
inline const std::vector<Setting_info>& matching_settings_registry()
{
  static const std::vector<Setting_info> registry = [] {
    using namespace internal;
    std::vector<Setting_info> r;
#define CGAL_SMC_SETTING_INFO(NAME, TYPE, DEFAULT, GIVEN_DEFAULT, RANGE, STAGE, DOC)                                   \
  r.push_back({#NAME, Setting_traits<TYPE>::type_name(), Setting_traits<TYPE>::text(DEFAULT),                           \
               Setting_traits<TYPE>::text(GIVEN_DEFAULT), range_text<TYPE>(RANGE), Matching_stage::STAGE, DOC});
    CGAL_SMC_SETTINGS(CGAL_SMC_SETTING_INFO)
#undef CGAL_SMC_SETTING_INFO
    return r;
  }();
  return registry;
}

} // namespace Surface_mesh_correspondence
} // namespace CGAL

#endif // CGAL_SURFACE_MESH_CORRESPONDENCE_MATCHING_SETTINGS_H
