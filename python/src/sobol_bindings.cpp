// stickslip._stickslip.sobol_indices: the library's Sobol' estimators
// (uncertainty/sobol.hpp) on outputs computed elsewhere, for the test that
// compares them with OpenTURNS on the same sample
// (tests/python/test_sobol_openturns.py).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <fmt/format.h>

#include <string>
#include <vector>

#include "bindings.hpp"
#include "stickslip/error.hpp"
#include "stickslip/uncertainty/sobol.hpp"

namespace stickslip::python {
namespace {

using column = py::array_t<double, py::array::c_style | py::array::forcecast>;

py::tuple bounds(const interval_estimate& e) { return py::make_tuple(e.low, e.high); }

void put(py::dict& d, const char* name, const std::vector<interval_estimate>& v) {
  py::list values, intervals;
  for (const auto& e : v) {
    values.append(e.value);
    intervals.append(bounds(e));
  }
  d[name] = values;
  d[fmt::format("{}_ci95", name).c_str()] = intervals;
}

// y_a, y_a2, y_b: shape (N,); y_e: shape (N, d), column i the outputs at
// A with input i from B (sobol.hpp's row layout).
py::dict sobol_indices_py(const column& y_a, const column& y_a2, const column& y_b,
                          const column& y_e, const std::string& form) {
  if (y_a.ndim() != 1 || y_a2.ndim() != 1 || y_b.ndim() != 1 || y_e.ndim() != 2)
    throw invalid_value("y_a, y_a2, y_b, y_e", "their shapes", "(N,), (N,), (N,) and (N, d)");
  const auto rows = static_cast<std::size_t>(y_a.shape(0));
  if (static_cast<std::size_t>(y_a2.shape(0)) != rows ||
      static_cast<std::size_t>(y_b.shape(0)) != rows ||
      static_cast<std::size_t>(y_e.shape(0)) != rows)
    throw invalid_value("y_a, y_a2, y_b, y_e", "their lengths", "the same number of rows N");
  first_order_form f{};
  if (form == "openturns_saltelli")
    f = first_order_form::openturns_saltelli;
  else if (form == "saltelli_2010")
    f = first_order_form::saltelli_2010;
  else
    throw invalid_value("form", form, "openturns_saltelli or saltelli_2010");
  const auto d = static_cast<std::size_t>(y_e.shape(1));
  sobol_moments m(d);
  const auto a = y_a.unchecked<1>(), a2 = y_a2.unchecked<1>(), b = y_b.unchecked<1>();
  const auto e = y_e.unchecked<2>();
  std::vector<double> row(d);
  for (std::size_t j = 0; j < rows; ++j) {
    for (std::size_t i = 0; i < d; ++i)
      row[i] = e(static_cast<py::ssize_t>(j), static_cast<py::ssize_t>(i));
    const auto jj = static_cast<py::ssize_t>(j);
    m.add(a(jj), a2(jj), b(jj), row);
  }
  const sobol_estimates s = sobol_indices(m, f);
  py::dict out;
  out["rows"] = s.rows;
  out["mean"] = s.mean;
  out["variance"] = s.variance;
  out["intrinsic_variance"] = s.intrinsic_variance;
  put(out, "first_order", s.first_order);
  put(out, "total_order", s.total_order);
  put(out, "response_first_order", s.response_first_order);
  out["parameter_share"] = s.parameter_share.value;
  out["parameter_share_ci95"] = bounds(s.parameter_share);
  out["intrinsic_share"] = s.intrinsic_share.value;
  out["intrinsic_share_ci95"] = bounds(s.intrinsic_share);
  return out;
}

}  // namespace

void register_sobol(py::module_& m) {
  m.def("sobol_indices", &sobol_indices_py, py::arg("y_a"), py::arg("y_a2"), py::arg("y_b"),
        py::arg("y_e"), py::arg("form") = "openturns_saltelli",
        "Sobol' indices and 95 % intervals of pick-freeze outputs (uncertainty/sobol.hpp)");
}

}  // namespace stickslip::python
