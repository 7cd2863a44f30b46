// A small streaming JSON emitter (no JSON library is in our dependency list).
// Doubles are printed with fmt "{}", the shortest text that parses back to the
// same double (round-trip exact); NaN and infinities become null, since JSON
// has no such numbers. Strings are escaped per RFC 8259; bytes that are not
// valid UTF-8 become U+FFFD so the output is always valid JSON.
// Objects and arrays are either multi-line (one member per line, indented by
// two spaces per level) or inline ({"a": 1, "b": 2}).
#pragma once
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "stickslip/io/atomic_file.hpp"
#include "stickslip/parameters.hpp"

namespace stickslip::io::detail {

// The JSON string literal for `s`, quotes included.
void append_json_string(text_sink& out, std::string_view s);
[[nodiscard]] std::string json_string(std::string_view s);
// The JSON number for `x`, or null when x is not finite.
[[nodiscard]] std::string json_number(double x);

enum class layout { multi_line, inline_ };

class json_emitter {
 public:
  // `base_indent`: levels of indentation to add to every line, for emitting
  // a value that will sit inside a larger document.
  explicit json_emitter(text_sink& out, std::size_t base_indent = 0)
      : out_(out), base_indent_(base_indent) {}

  void begin_object(layout l = layout::inline_) { open('{', l); }
  void end_object() { close('}'); }
  void begin_array(layout l = layout::inline_) { open('[', l); }
  void end_array() { close(']'); }
  void key(std::string_view k);

  void value(double x);
  void value(std::uint64_t x);
  void value(std::int64_t x);
  void value(int x) { value(static_cast<std::int64_t>(x)); }
  void value(bool b);
  void value(std::string_view s);
  void value(const char* s) { value(std::string_view(s)); }
  void null();

  template <class T>
  void member(std::string_view k, const T& v) {
    key(k);
    value(v);
  }
  // Depth of open containers (0 at top level).
  [[nodiscard]] std::size_t depth() const noexcept { return stack_.size(); }

 private:
  struct level {
    layout kind;
    bool empty;
  };
  void before_value();
  void newline_indent(std::size_t depth);
  void open(char bracket, layout l);
  void close(char bracket);

  text_sink& out_;
  std::size_t base_indent_;
  std::vector<level> stack_;
  bool after_key_ = false;
};

// The members of a model description: every recorded scalar
// (recorded_parameter_names, resolved: mu_s of a model without one is mu),
// null for a symbol in `swept`, left out for a symbol in `omitted` (one that
// does not define the model); then the resolved belt: "belt_levels" [v_i],
// "belt_generator" [[q_ij]] and, for two levels, "belt_rates" [r1, r2],
// each null when it is not one for the whole result (`same_levels`,
// `same_generator`: a swept lambda, V, vI or rI, or one drawn by a law).
void emit_model_members(json_emitter& j, const model_parameters& p,
                        const std::vector<std::string>& swept = {},
                        const std::vector<std::string>& omitted = {},
                        bool same_levels = true, bool same_generator = true);

}  // namespace stickslip::io::detail
