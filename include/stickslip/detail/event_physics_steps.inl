// Private forwarding text, not installed: src/core/fast_lanes.cpp still
// includes this old path into each SIMD target's namespace. The text is
// public now as stickslip/event_physics_steps.inl (no include guard, like
// it); delete this file once fast_lanes.cpp includes that.
#include "stickslip/event_physics_steps.inl"
