#include "json_emitter.hpp"

#include <algorithm>

#include <cmath>

namespace stickslip::io::detail {
namespace {

// Length of the valid UTF-8 sequence starting at s[i], or 0 if invalid
// (overlong forms, surrogates and code points above U+10FFFF are invalid).
std::size_t utf8_sequence_length(std::string_view s, std::size_t i) {
  const auto b = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char c = b(i);
  std::size_t n;
  unsigned lo = 0x80, hi = 0xBF;  // allowed range of the second byte
  if (c >= 0xC2 && c <= 0xDF) {
    n = 2;
  } else if (c >= 0xE0 && c <= 0xEF) {
    n = 3;
    if (c == 0xE0) lo = 0xA0;
    if (c == 0xED) hi = 0x9F;
  } else if (c >= 0xF0 && c <= 0xF4) {
    n = 4;
    if (c == 0xF0) lo = 0x90;
    if (c == 0xF4) hi = 0x8F;
  } else {
    return 0;
  }
  if (i + n > s.size()) return 0;
  if (b(i + 1) < lo || b(i + 1) > hi) return 0;
  for (std::size_t k = 2; k < n; ++k)
    if (b(i + k) < 0x80 || b(i + k) > 0xBF) return 0;
  return n;
}

}  // namespace

void append_json_string(text_sink& out, std::string_view s) {
  out.put('"');
  for (std::size_t i = 0; i < s.size();) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c < 0x80) {
      switch (c) {
        case '"': out.write("\\\""); break;
        case '\\': out.write("\\\\"); break;
        case '\b': out.write("\\b"); break;
        case '\f': out.write("\\f"); break;
        case '\n': out.write("\\n"); break;
        case '\r': out.write("\\r"); break;
        case '\t': out.write("\\t"); break;
        default:
          if (c < 0x20 || c == 0x7F)
            out.print("\\u{:04x}", static_cast<unsigned>(c));
          else
            out.put(static_cast<char>(c));
      }
      ++i;
      continue;
    }
    const std::size_t n = utf8_sequence_length(s, i);
    if (n == 0) {
      out.write("\\ufffd");  // not UTF-8: replacement character
      ++i;
    } else {
      out.write(s.substr(i, n));
      i += n;
    }
  }
  out.put('"');
}

std::string json_string(std::string_view s) {
  text_sink t;
  append_json_string(t, s);
  return t.str();
}

std::string json_number(double x) {
  // fmt's "{}" is the shortest round-trip representation (Dragonbox), always
  // a valid JSON number for finite x: "1", "0.1", "1e-07", "1.5e+300".
  return std::isfinite(x) ? fmt::format("{}", x) : std::string("null");
}

void json_emitter::newline_indent(std::size_t depth) {
  out_.put('\n');
  for (std::size_t i = 0; i < base_indent_ + depth; ++i) out_.write("  ");
}

void json_emitter::before_value() {
  if (after_key_) {
    after_key_ = false;
    return;
  }
  if (stack_.empty()) return;
  auto& top = stack_.back();
  if (!top.empty) out_.put(',');
  if (top.kind == layout::multi_line)
    newline_indent(stack_.size());
  else if (!top.empty)
    out_.put(' ');
  top.empty = false;
}

void json_emitter::open(char bracket, layout l) {
  before_value();
  out_.put(bracket);
  stack_.push_back({l, true});
}

void json_emitter::close(char bracket) {
  const level top = stack_.back();
  stack_.pop_back();
  if (top.kind == layout::multi_line && !top.empty) newline_indent(stack_.size());
  out_.put(bracket);
}

void json_emitter::key(std::string_view k) {
  before_value();
  append_json_string(out_, k);
  out_.write(": ");
  after_key_ = true;
}

void json_emitter::value(double x) {
  before_value();
  out_.write(json_number(x));
}
void json_emitter::value(std::uint64_t x) {
  before_value();
  out_.print("{}", x);
}
void json_emitter::value(std::int64_t x) {
  before_value();
  out_.print("{}", x);
}
void json_emitter::value(bool b) {
  before_value();
  out_.write(b ? "true" : "false");
}
void json_emitter::value(std::string_view s) {
  before_value();
  append_json_string(out_, s);
}
void json_emitter::null() {
  before_value();
  out_.write("null");
}

void emit_model_members(json_emitter& j, const model_parameters& p,
                        const std::vector<std::string>& swept,
                        const std::vector<std::string>& omitted, bool same_levels,
                        bool same_generator) {
  for (const char* sym : recorded_parameter_names) {
    if (std::find(omitted.begin(), omitted.end(), sym) != omitted.end()) continue;
    if (std::find(swept.begin(), swept.end(), sym) != swept.end()) {
      j.key(sym);
      j.null();
    } else {
      j.member(sym, parameter_value(p, sym));
    }
  }
  const auto levels = p.levels();
  const auto q = p.generator();
  const std::size_t n = levels.size();
  j.key("belt_levels");
  if (!same_levels) {
    j.null();
  } else {
    j.begin_array();
    for (double v : levels) j.value(v);
    j.end_array();
  }
  j.key("belt_generator");
  if (!same_generator) {
    j.null();
  } else {
    j.begin_array();
    for (std::size_t i = 0; i < n; ++i) {
      j.begin_array();
      for (std::size_t k = 0; k < n; ++k) j.value(q[i * n + k]);
      j.end_array();
    }
    j.end_array();
  }
  if (n == 2) {
    j.key("belt_rates");
    if (!same_generator) {
      j.null();
    } else {
      j.begin_array();
      j.value(q[1]);
      j.value(q[2]);
      j.end_array();
    }
  }
}

}  // namespace stickslip::io::detail
