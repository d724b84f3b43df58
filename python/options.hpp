#pragma once
// Binding an options field: its name, its library default (the struct's own), and its help.
#include <string>
#include <type_traits>
#include <variant>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>  // std::optional fields: None when unset

#include "core/option_table.hpp"

// c.def_readwrite("name", &Type::name, doc)
#define PK_FIELD(cls, Type, name, doc) (cls).def_readwrite(#name, &Type::name, doc)

namespace plumekit::python {

// Every entry of an options table (core/option_table.hpp) as a read-write
// property named by the entry's last part ("flow.nu" -> nu), with its help as
// the doc; enum fields read and write their names through the library's parser.
template <class T>
void bind_table(pybind11::class_<T>& c, const OptionTable<T>& table) {
  for (const OptionEntry<T>& e : table.entries) {
    const std::string doc = e.help + " (default " + default_text(e) + ")";
    std::visit(
        [&](const auto& field) {
          using F = std::decay_t<decltype(field)>;
          if constexpr (std::is_same_v<F, EnumField<T>>)
            c.def_property(
                e.key().c_str(), [get = field.get](const T& o) { return get(o); },
                [set = field.set](T& o, const std::string& v) { set(o, v); }, doc.c_str());
          else if constexpr (std::is_same_v<F, OptionalField<T>>)
            c.def_readwrite(e.key().c_str(), field.field, doc.c_str());
          else
            c.def_readwrite(e.key().c_str(), field, doc.c_str());
        },
        e.field);
  }
}

}  // namespace plumekit::python
