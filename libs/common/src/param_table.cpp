#include "roadslam/common/param_table.h"

#include "roadslam/common/config.h"

namespace roadslam {

std::string listOfNames(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) out += i + 1 == names.size() ? " or " : ", ";
    out += names[i];
  }
  return out;
}

ParamTable ParamTable::reader(const mrpt::config::CConfigFileBase& cfg, const std::string& section) {
  return ParamTable(Mode::Load, &cfg, nullptr, section);
}

ParamTable ParamTable::writer(mrpt::config::CConfigFileBase& cfg, const std::string& section) {
  return ParamTable(Mode::Save, nullptr, &cfg, section);
}

ParamTable ParamTable::lister() { return ParamTable(Mode::List, nullptr, nullptr, ""); }

void ParamTable::num(const std::string& key, double& v) { scaled(key, v, 1.0); }  // x / 1 * 1 == x

void ParamTable::num(const std::string& key, std::int64_t& v) {
  keys_.push_back(key);
  if (mode_ == Mode::Load) v = static_cast<std::int64_t>(readDouble(*in_, section_, key, static_cast<double>(v)));
  if (mode_ == Mode::Save) out_->write(section_, key, std::to_string(v));
}

void ParamTable::integer(const std::string& key, int& v) {
  keys_.push_back(key);
  if (mode_ == Mode::Load) v = readInt(*in_, section_, key, v);
  if (mode_ == Mode::Save) out_->write(section_, key, v);
}

// As the components always converted: load `ini * f` with the field's own value as the default in
// ini units, save `si / f` (so 10 degrees is saved as 10.000000).
void ParamTable::scaled(const std::string& key, double& v, double si_per_unit) {
  keys_.push_back(key);
  if (mode_ == Mode::Load) v = readDouble(*in_, section_, key, v / si_per_unit) * si_per_unit;
  if (mode_ == Mode::Save) out_->write(section_, key, v / si_per_unit);
}

void ParamTable::flag(const std::string& key, bool& v) {
  keys_.push_back(key);
  if (mode_ == Mode::Load) v = readBool(*in_, section_, key, v);
  if (mode_ == Mode::Save) out_->write(section_, key, v);
}

void ParamTable::text(const std::string& key, std::string& v) {
  keys_.push_back(key);
  if (mode_ == Mode::Load) v = readString(*in_, section_, key, v);
  if (mode_ == Mode::Save) out_->write(section_, key, v);
}

std::string ParamTable::keyLocation(const std::string& key) const {
  return in_ ? roadslam::keyLocation(*in_, section_, key) : "[" + section_ + "] " + key;
}

std::string ParamTable::pickAlias(const std::string& key, const std::string& alias) const {
  const bool k = !in_->read_string(section_, key, "", false).empty();
  const bool a = !in_->read_string(section_, alias, "", false).empty();
  if (k && a) {
    const auto* f = dynamic_cast<const CheckedConfig*>(in_);
    const int line = f ? f->lineOf(section_, key) : 0;
    const std::string where = line > 0 ? "line " + std::to_string(line) : "the section";
    requireValue(false, *in_, section_, alias, "alias of '" + key + "', which " + where + " sets too: set only one");
  }
  return a ? alias : key;
}

void ParamTable::numOrAlias(const std::string& key, const std::string& alias, double& v, double si_per_unit) {
  if (mode_ == Mode::Load) {
    keys_.push_back(key);
    v = readDouble(*in_, section_, pickAlias(key, alias), v / si_per_unit) * si_per_unit;
  } else {
    scaled(key, v, si_per_unit);
  }
  keys_.push_back(alias);
}

void ParamTable::numOrAlias(const std::string& key, const std::string& alias, int& v) {
  if (mode_ == Mode::Load) {
    keys_.push_back(key);
    v = readInt(*in_, section_, pickAlias(key, alias), v);
  } else {
    integer(key, v);
  }
  keys_.push_back(alias);
}

}  // namespace roadslam
