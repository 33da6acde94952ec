#pragma once
/// \file param_table.h
/// One description of a Params struct's ini keys, used to load, to save and to list the known keys.
/// A component writes its table once:
///
///     void Params::fields(ParamTable& t) {
///       t.num("map_voxel_m", map_voxel_m);                    // SI inside, the unit in the key
///       t.angle("keyframe_angle_deg", keyframe_angle_rad);    // degrees in the ini, radians inside
///       t.flag("deskew", deskew);
///       t.choice("matcher", matcher, matcherNames());         // an enum by name, from one table
///     }
///
/// and loads with `loadFields(*this, cfg, section)`, saves with `saveFields(*this, cfg, section)`,
/// lists its keys with `fieldKeys<Params>()`. Range checks stay in loadFromConfigFile, after the load.
/// Saved text is what CConfigFileBase::write gives for the field's type (doubles "%f", or "%e" outside
/// [1e-4, 1e4]), so a saved config_used.ini is the same as when each component wrote its keys by hand.

#include <mrpt/config/CConfigFileBase.h>

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace roadslam {

/// Ini units: the SI value of one ini unit. Loading multiplies by it, saving divides by it.
namespace unit {
constexpr double kDeg = M_PI / 180.0;  ///< degrees -> radians
constexpr double kMs = 1e-3;           ///< milliseconds -> seconds
constexpr double kUs = 1e-6;           ///< microseconds -> seconds
constexpr double kMb = 1e6;            ///< megabytes -> bytes
constexpr double kKmh = 1 / 3.6;       ///< km/h -> m/s
constexpr double kKnot = 1852.0 / 3600.0;  ///< international knots -> m/s (NMEA RMC speed)
}  // namespace unit

/// The names of an enum's values: toString and fromString both read this one table.
template <class E>
using NameTable = std::vector<std::pair<E, const char*>>;

/// "a, b or c": the valid names, for error messages.
std::string listOfNames(const std::vector<std::string>& names);

/// The name of \p v in \p table (std::logic_error when the table lacks it: a programming error).
template <class E>
std::string nameOf(const NameTable<E>& table, E v) {
  for (const auto& [value, name] : table)
    if (value == v) return name;
  throw std::logic_error("an enum value has no name in its table");
}

/// The names of \p table, in order.
template <class E>
std::vector<std::string> namesOf(const NameTable<E>& table) {
  std::vector<std::string> names;
  for (const auto& [value, n] : table) names.emplace_back(n);
  return names;
}

/// The value named \p name; std::invalid_argument "<what> = '<name>': expected a, b or c" otherwise.
template <class E>
E valueOf(const NameTable<E>& table, const std::string& name, const std::string& what) {
  for (const auto& [value, n] : table)
    if (name == n) return value;
  throw std::invalid_argument(what + " = '" + name + "': expected " + listOfNames(namesOf(table)));
}

/// One section of an ini, seen by a Params' fields(): each call loads, saves or lists one key.
class ParamTable {
 public:
  /// A table that reads \p section of \p cfg into the fields (absent keys keep the field's value).
  static ParamTable reader(const mrpt::config::CConfigFileBase& cfg, const std::string& section);
  /// A table that writes the fields into \p section of \p cfg.
  static ParamTable writer(mrpt::config::CConfigFileBase& cfg, const std::string& section);
  /// A table that only collects the keys (keys()).
  static ParamTable lister();

  /// A number with its unit in the key (SI): "max_range_m". Integer fields (int, size_t, uint16_t,
  /// the uint64_t seeds) are read and written as int, as the components always did.
  void num(const std::string& key, double& v);
  template <class I, std::enable_if_t<std::is_integral_v<I> && !std::is_same_v<I, bool>, int> = 0>
  void num(const std::string& key, I& v) {
    int i = static_cast<int>(v);
    integer(key, i);
    if (loading()) v = static_cast<I>(i);
  }
  /// A 64-bit count (a Unix time [s]): read as a number, written exactly (std::to_string, not "%e").
  void num(const std::string& key, std::int64_t& v);
  /// A number in another unit in the ini: the ini value times \p si_per_unit is the field [SI].
  void scaled(const std::string& key, double& v, double si_per_unit);
  /// An angle: degrees in the ini ("_deg" key), radians in the field.
  void angle(const std::string& key, double& rad) { scaled(key, rad, unit::kDeg); }
  void flag(const std::string& key, bool& v);
  void text(const std::string& key, std::string& v);
  /// An enum by name: an unknown name is an error "FILE:LINE: [section] key = 'name': expected a, b or c".
  template <class E>
  void choice(const std::string& key, E& v, const NameTable<E>& names) {
    std::string s = nameOf(names, v);
    text(key, s);
    if (!loading()) return;
    for (const auto& [value, n] : names)
      if (s == n) {
        v = value;
        return;
      }
    throw std::runtime_error(keyLocation(key) + " = '" + s + "': expected " + listOfNames(namesOf(names)));
  }
  /// A number read from \p key, or from its older name \p alias (same unit) when only that is set
  /// (both is an error); saved under \p key.
  void numOrAlias(const std::string& key, const std::string& alias, double& v, double si_per_unit = 1.0);
  void numOrAlias(const std::string& key, const std::string& alias, int& v);

  bool loading() const { return mode_ == Mode::Load; }
  const std::string& section() const { return section_; }
  /// Every key named so far, in order (both names of an aliased key).
  const std::vector<std::string>& keys() const { return keys_; }

 private:
  enum class Mode { Load, Save, List };
  ParamTable(Mode m, const mrpt::config::CConfigFileBase* in, mrpt::config::CConfigFileBase* out,
             std::string section)
      : mode_(m), in_(in), out_(out), section_(std::move(section)) {}
  void integer(const std::string& key, int& v);
  /// "FILE:LINE: [section] key" for error messages (config.h keyLocation).
  std::string keyLocation(const std::string& key) const;
  /// Which of key/alias a load reads; both set is an error
  /// "FILE:LINE: [section] alias = v: alias of 'key', which line N sets too: set only one".
  std::string pickAlias(const std::string& key, const std::string& alias) const;

  Mode mode_;
  const mrpt::config::CConfigFileBase* in_;
  mrpt::config::CConfigFileBase* out_;
  std::string section_;
  std::vector<std::string> keys_;
};

/// Loads \p p's fields() from \p section.
template <class P>
void loadFields(P& p, const mrpt::config::CConfigFileBase& cfg, const std::string& section) {
  ParamTable t = ParamTable::reader(cfg, section);
  p.fields(t);
}

/// Saves \p p's fields() into \p section (fields() runs on a copy, so it needs no const twin).
template <class P>
void saveFields(const P& p, mrpt::config::CConfigFileBase& cfg, const std::string& section) {
  P copy = p;
  ParamTable t = ParamTable::writer(cfg, section);
  copy.fields(t);
}

/// The keys of P's table, in order: for the unknown-key checks.
template <class P>
std::vector<std::string> fieldKeys() {
  P p;
  ParamTable t = ParamTable::lister();
  p.fields(t);
  return t.keys();
}

}  // namespace roadslam
