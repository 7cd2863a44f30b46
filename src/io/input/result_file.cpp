// A finished output read generically (io/result_file.hpp).
#include "stickslip/io/result_file.hpp"

#include <netcdf>

#include <fmt/format.h>

#include <algorithm>
#include <numeric>

#include "../netcdf_file.hpp"
#include "stickslip/error.hpp"

namespace stickslip::io {
namespace nc = netCDF;

struct result_file::handle {
  explicit handle(const std::string& path) : file(path, nc::NcFile::read) {}
  detail::nc_file file;
};

namespace {

// A text attribute of a variable, "" when absent or not text.
std::string text_attribute(const nc::NcVar& v, const std::string& name) {
  const auto atts = v.getAtts();
  const auto it = atts.find(name);
  if (it == atts.end() || it->second.getType().getTypeClass() != nc::NcType::nc_CHAR) return "";
  std::string s;
  it->second.getValues(s);
  while (!s.empty() && s.back() == '\0') s.pop_back();
  return s;
}

result_variable describe(const nc::NcVar& v) {
  result_variable r;
  r.name = v.getName();
  for (const auto& d : v.getDims()) r.dims.push_back(d.getName());
  r.units = text_attribute(v, "units");
  r.long_name = text_attribute(v, "long_name");
  r.symbol = text_attribute(v, "symbol");
  r.coordinates = text_attribute(v, "coordinates");
  r.text = v.getType().getTypeClass() == nc::NcType::nc_STRING;
  return r;
}

}  // namespace

result_file::result_file(const std::string& path) : path_(path) {
  try {
    nc_ = std::make_unique<handle>(path);
  } catch (const nc::exceptions::NcException& e) {
    throw error(exit_code::invalid_input,
                fmt::format("cannot read '{}' as a NetCDF file: {}", path, detail::netcdf_message(e)));
  }
  for (const auto& [name, dim] : nc_->file.getDims()) dims_.push_back({name, dim.getSize()});
  std::vector<nc::NcVar> vars;
  for (const auto& [name, var] : nc_->file.getVars()) vars.push_back(var);
  // In the file's order (the writer's), not by name.
  std::sort(vars.begin(), vars.end(),
            [](const nc::NcVar& a, const nc::NcVar& b) { return a.getId() < b.getId(); });
  for (const auto& v : vars) vars_.push_back(describe(v));
}

result_file::~result_file() = default;
result_file::result_file(result_file&&) noexcept = default;
result_file& result_file::operator=(result_file&&) noexcept = default;

const result_dimension* result_file::dimension(const std::string& name) const noexcept {
  for (const auto& d : dims_)
    if (d.name == name) return &d;
  return nullptr;
}

const result_variable* result_file::variable(const std::string& name) const noexcept {
  for (const auto& v : vars_)
    if (v.name == name) return &v;
  return nullptr;
}

std::vector<double> result_file::coordinate(const std::string& dim) const {
  const auto* d = dimension(dim);
  if (!d) throw error(exit_code::internal, fmt::format("no dimension '{}' in {}", dim, path_));
  const auto* v = variable(dim);
  if (v && !v->text && v->dims == std::vector<std::string>{dim}) return values(dim);
  std::vector<double> index(d->size);
  std::iota(index.begin(), index.end(), 0.0);
  return index;
}

std::vector<double> result_file::values(const std::string& var) const {
  const auto v = nc_->file.getVar(var);
  if (v.isNull()) throw error(exit_code::internal, fmt::format("no variable '{}' in {}", var, path_));
  std::size_t n = 1;
  for (const auto& d : v.getDims()) n *= d.getSize();
  std::vector<double> out(n);
  if (n > 0) v.getVar(out.data());
  return out;
}

std::vector<std::string> result_file::strings(const std::string& var) const {
  const auto v = nc_->file.getVar(var);
  if (v.isNull()) throw error(exit_code::internal, fmt::format("no variable '{}' in {}", var, path_));
  std::size_t n = 1;
  for (const auto& d : v.getDims()) n *= d.getSize();
  std::vector<char*> raw(n, nullptr);
  if (n > 0) v.getVar(raw.data());
  std::vector<std::string> out;
  for (char* s : raw) out.emplace_back(s ? s : "");
  if (n > 0) nc_free_string(n, raw.data());
  return out;
}

std::string result_file::attribute(const std::string& name) const {
  const auto atts = nc_->file.getAtts();
  const auto it = atts.find(name);
  if (it == atts.end() || it->second.getType().getTypeClass() != nc::NcType::nc_CHAR) return "";
  std::string s;
  it->second.getValues(s);
  return s;
}

}  // namespace stickslip::io
