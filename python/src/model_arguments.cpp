// The model from keyword arguments and back (bindings.hpp).
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "stickslip/io/config.hpp"

namespace stickslip::python {

std::string list_text(const std::vector<double>& values) {
  return fmt::format("{}", fmt::join(values, ","));
}

model_parameters parameters_from(const py::dict& model, model_parameters p,
                                 std::vector<uncertain_parameter>* laws, const char* refusal) {
  if (model.contains("belt_levels") && !model["belt_levels"].is_none())
    p.belt_levels =
        io::parse_belt_levels(list_text(py::cast<std::vector<double>>(model["belt_levels"])));
  if (model.contains("belt_rates") && !model["belt_rates"].is_none())
    p.belt_rates = io::parse_value_list("--belt-rates",
                                        list_text(py::cast<std::vector<double>>(model["belt_rates"])));
  if (model.contains("belt_generator") && !model["belt_generator"].is_none()) {
    const auto rows = py::cast<std::vector<std::vector<double>>>(model["belt_generator"]);
    if (rows.empty())
      throw invalid_value("--belt-generator", "", "a square matrix: 0 rows need 0 rates each");
    std::string text;
    for (std::size_t i = 0; i < rows.size(); ++i) text += (i ? ";" : "") + list_text(rows[i]);
    p.belt_generator = io::parse_belt_generator(text);
  }
  std::vector<parameter_assignment> scalars;
  for (const auto& [key, value] : model) {
    auto sym = py::cast<std::string>(key);
    if (sym == "belt_levels" || sym == "belt_rates" || sym == "belt_generator") continue;
    if (py::isinstance<py::str>(value)) {
      const auto text = py::cast<std::string>(value);
      if (!laws) throw invalid_value(flag_of(sym), text, refusal);
      laws->push_back({sym, parse_law(text, flag_of(sym))});
      continue;
    }
    scalars.push_back({std::move(sym), py::cast<double>(value)});
  }
  if (laws) io::sort_laws(*laws);
  return assign(std::move(p), std::move(scalars));
}

py::dict model_dict(const model_parameters& p) {
  py::dict d;
  for (const char* sym : recorded_parameter_names) d[sym] = parameter_value(p, sym);
  const auto levels = p.levels();
  const auto q = p.generator();
  const std::size_t n = levels.size();
  d["belt_levels"] = levels;
  py::list rows;
  for (std::size_t i = 0; i < n; ++i)
    rows.append(std::vector<double>(q.begin() + static_cast<std::ptrdiff_t>(i * n),
                                    q.begin() + static_cast<std::ptrdiff_t>((i + 1) * n)));
  d["belt_generator"] = rows;
  if (n == 2) d["belt_rates"] = std::vector<double>{q[1], q[2]};
  return d;
}

int belt_start_from(const std::string& text, const model_parameters& p) {
  return io::parse_belt_start("--belt-start", text, p.levels().size());
}

}  // namespace stickslip::python
