// The identity of a record layout (record_schema.hpp).
#include "stickslip/record_schema.hpp"

#include "fnv1a.hpp"

namespace stickslip {

std::uint64_t record_layout_id(std::span<const record_field> fields) noexcept {
  detail::fnv1a f;
  for (const auto& field : fields) {
    f.add(field.name);
    f.byte(static_cast<unsigned char>(field.member.index()));  // the member's type and struct
  }
  return f.h;
}

}  // namespace stickslip
