// A small document model for the reproduction report, rendered both to
// Markdown and to self-contained HTML (PNG figures embedded as base64 data
// URIs). Internal to src/io.
#pragma once
#include <string>
#include <vector>

namespace stickslip::study::detail {

struct doc_block {
  enum class kind { heading, paragraph, table, image, code, list } type;
  int level = 0;                                // heading level
  std::string text;                             // heading, paragraph, code, image title
  std::vector<std::vector<std::string>> rows;   // table: first row is the header
  std::vector<std::string> items;               // list
  std::string path;                             // image: relative to the report folder
  std::string caption;                          // image
};

class document {
 public:
  void heading(int level, std::string text);
  void paragraph(std::string text);
  void table(std::vector<std::vector<std::string>> rows);
  void image(std::string title, std::string path, std::string caption);
  void code(std::string text);
  void list(std::vector<std::string> items);

  // Markdown (GitHub flavour).
  [[nodiscard]] std::string markdown() const;
  // HTML; images are read from `base_dir/path` and embedded as data URIs
  // (a missing image becomes a note).
  [[nodiscard]] std::string html(const std::string& title, const std::string& base_dir) const;

 private:
  std::vector<doc_block> blocks_;
};

[[nodiscard]] std::string base64(const std::string& bytes);
[[nodiscard]] std::string html_escape(const std::string& s);

}  // namespace stickslip::study::detail
