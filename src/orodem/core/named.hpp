// Named<E>: a value of an enum with its name in configs, command lines and
// outputs. A table of them is parsed once at the boundary (the config
// loader's Reader::choice, a command's option); the rest of the program
// compares enums and writes name_in(table, value).
#pragma once

#include <concepts>
#include <cstddef>
#include <string_view>
#include <type_traits>

#include <fmt/format.h>

namespace orodem {

template <class E>
struct Named {
    E value;
    const char* name;
};

template <class E, std::size_t N>
constexpr const char* name_in(const Named<E> (&table)[N], E v) {
    for (const Named<E>& n : table)
        if (n.value == v) return n.name;
    return "?";
}

/// The value named `name`, or false when the table has no such name.
template <class E, std::size_t N>
constexpr bool value_in(const Named<E> (&table)[N], std::string_view name, E& out) {
    for (const Named<E>& n : table)
        if (name == n.name) {
            out = n.value;
            return true;
        }
    return false;
}

/// An enum with a name_of(value) (found by argument-dependent lookup).
template <class E>
concept NamedEnum = std::is_enum_v<E> && requires(E e) {
    { name_of(e) } -> std::convertible_to<const char*>;
};

}  // namespace orodem

/// fmt writes a named enum as its name.
template <orodem::NamedEnum E>
struct fmt::formatter<E> : fmt::formatter<std::string_view> {
    auto format(E v, fmt::format_context& ctx) const {
        return fmt::formatter<std::string_view>::format(name_of(v), ctx);
    }
};
