// The pybind11 extension behind the stickslip Python package: a thin layer
// over the library, one binding file per command (simulate_bindings.cpp,
// sweep_bindings.cpp, peak_bindings.cpp, sobol_bindings.cpp; what they share
// is bindings.hpp). This file makes the module: its error type, and the
// library's tables and limits that the pure-Python package (python/stickslip)
// reads, so that its keywords, checks and columns come from the same rows.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "stickslip/error.hpp"
#include "stickslip/estimates.hpp"
#include "stickslip/io/config.hpp"
#include "stickslip/nearest_name.hpp"
#include "stickslip/record_schema.hpp"
#include "stickslip/statistics_schema.hpp"
#include "stickslip/sweep_spec.hpp"
#include "stickslip/version.hpp"

namespace py = pybind11;
using namespace stickslip;
using stickslip::python::model_dict;
using stickslip::python::parameters_from;

PYBIND11_MODULE(_stickslip, m) {
  m.doc() = "stickslip's compiled core (use the stickslip package, not this module)";
  m.attr("__version__") = stickslip::version;
  m.attr("git_revision") = stickslip::git_revision;
  static py::exception<stickslip::error> error_type(m, "Error", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const stickslip::error& e) {
      py::object err = py::reinterpret_borrow<py::object>(error_type.ptr())(e.what());
      err.attr("exit_code") = static_cast<int>(e.code());
      PyErr_SetObject(error_type.ptr(), err.ptr());
    }
  });
  // The command line's parser of whole numbers, for the Python layer's one
  // coercion of integer arguments (stickslip/_parameters.py): its rule and
  // its message.
  m.def("parse_unsigned",
        [](const std::string& name, const std::string& text, std::uint64_t lo, std::uint64_t hi) {
          return io::parse_unsigned(name, text, lo, hi);
        },
        py::arg("name"), py::arg("text"), py::arg("lo"), py::arg("hi"));
  // The command line's parser of a swept parameter's values (--lambda
  // log:0.1:30:40): sweep(lam="log:0.1:30:40") gives the CLI's axis, bit
  // for bit (np.logspace's values differ in their last bits, and the streams
  // are keyed by them), with its checks and messages.
  m.def("parse_axis",
        [](const std::string& name, const std::string& symbol, const std::string& text) {
          return io::parse_grid(name, text, io::grid_domain_of(symbol));
        },
        py::arg("name"), py::arg("symbol"), py::arg("text"));
  m.attr("max_realizations") = stickslip::max_realizations;
  m.attr("max_block_size") = stickslip::max_block_size;
  m.attr("max_histogram_bins") = stickslip::max_histogram_bins;
  m.def("resolve_parameters", [](const py::dict& model) { return model_dict(parameters_from(model)); },
        py::arg("model"));
  // The parameter table (parameters.hpp, scalar_parameters): the Python
  // keywords, their defaults and units come from its rows.
  m.def("parameter_table", [] {
    py::list rows;
    const model_parameters defaults;
    for (const auto& row : scalar_parameters) {
      py::dict d;
      d["symbol"] = row.symbol;
      d["keyword"] = row.python_keyword ? row.python_keyword : row.symbol;
      d["long_name"] = row.long_name;
      d["description"] = row.description;
      d["units"] = row.units;
      d["default"] = defaults.*row.field;
      d["unset_means_mu"] = row.domain == parameter_domain::positive_or_unset;
      rows.append(d);
    }
    return rows;
  });
  // The CLI's warning of --mu beside --mu-s and --mu-k (only_in_the_stream_key),
  // for the keywords given ({symbol: a number, a list of numbers or a law's
  // text}), each as the command line would be given it; None when none.
  m.def("only_in_the_stream_key", [](const py::dict& given) -> py::object {
    std::vector<given_parameter> values;
    for (const auto& [key, value] : given) {
      std::string text;
      if (py::isinstance<py::str>(value)) text = py::cast<std::string>(value);
      else if (py::isinstance<py::sequence>(value))
        text = stickslip::python::list_text(py::cast<std::vector<double>>(value));
      else text = fmt::format("{}", py::cast<double>(value));
      values.push_back({py::cast<std::string>(key), std::move(text)});
    }
    const auto note = only_in_the_stream_key(values);
    return note.empty() ? py::none() : py::object(py::str(note));
  }, py::arg("given"));
  // How a keyword's text is told to be a law (parameter_law.hpp), as flags and TOML tell it.
  // The CLI's rule for "did you mean" (nearest_name.hpp), for misspelt keywords.
  m.def("nearest_name", [](const std::string& word, const std::vector<std::string>& names) {
        return nearest_name(word, names);
      }, py::arg("word"), py::arg("names"));
  m.def("looks_like_law", [](const std::string& text) { return looks_like_law(text); },
        py::arg("text"));
  m.attr("default_max_events") = stickslip::default_max_events;
  // The estimate table (estimates.hpp): the sweep's Dataset is results.nc,
  // which maps its rows; this lists them for the tests and the docs.
  m.def("estimate_kinds", [] {
    py::list rows;
    for (const auto& row : estimate_kinds()) {
      py::dict d;
      d["name"] = row.name;
      d["variable"] = row.variable;
      d["value_suffix"] = row.value_suffix;
      d["value_member"] = row.value_member;
      static constexpr const char* index_names[] = {"none", "belt_rate", "generator_entry", "axis"};
      d["index"] = index_names[static_cast<int>(row.index)];
      d["extra"] = extra_name(row.extra);
      py::list has;  // (results.nc name, summary.json name) of the quantities that have it
      for (const auto& q : quantities())
        if (row.has(q)) has.append(py::make_tuple(q.name, q.summary_name));
      d["quantities"] = has;
      rows.append(d);
    }
    return rows;
  });
  // The record table (record_schema.hpp): Realization.record maps its
  // outcome rows; this lists every row for the Python layer and the tests.
  m.def("record_fields", [] {
    static constexpr const char* role_names[] = {"identity", "outcome", "internal"};
    py::list rows;
    for (const auto& field : record_table) {
      py::dict d;
      d["name"] = field.name;
      d["symbol"] = field.symbol;
      d["units"] = field.units;
      d["description"] = field.description;
      d["role"] = role_names[static_cast<int>(field.role)];
      rows.append(d);
    }
    return rows;
  });
  python::register_simulate(m);
  python::register_sweep(m);
  python::register_peak(m);
  python::register_sobol(m);
}
