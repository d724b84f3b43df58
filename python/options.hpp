#pragma once
// Binding an options field: its name, its library default (the struct's own), and its help.
#include <algorithm>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>  // std::optional fields: None when unset

#include "core/option_table.hpp"

// c.def_readwrite("name", &Type::name, doc)
#define PK_FIELD(cls, Type, name, doc) (cls).def_readwrite(#name, &Type::name, doc)

namespace plumekit::python {

// Every entry of an options table (core/option_table.hpp) but those named in
// `skip` as a read-write property named by the entry's last part ("flow.nu" ->
// nu), with its help as the doc; enum fields read and write their names through
// the library's parser.
template <class T>
void bind_table(pybind11::class_<T>& c, const OptionTable<T>& table,
                const std::vector<std::string>& skip = {}) {
  for (const OptionEntry<T>& e : table.entries) {
    if (std::find(skip.begin(), skip.end(), e.name) != skip.end()) continue;
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

// `old_name`, a keyword kept for one release, reads and writes the property
// `new_name` (its table's name); writing it warns with a DeprecationWarning.
template <class T>
void bind_deprecated_alias(pybind11::class_<T>& c, const std::string& old_name,
                           const std::string& new_name) {
  c.def_property(
      old_name.c_str(),
      [new_name](const pybind11::object& self) { return self.attr(new_name.c_str()); },
      [old_name, new_name](const pybind11::object& self, const pybind11::object& value) {
        const std::string message = old_name + " is deprecated; use " + new_name;
        if (PyErr_WarnEx(PyExc_DeprecationWarning, message.c_str(), 1) != 0)
          throw pybind11::error_already_set();
        self.attr(new_name.c_str()) = value;
      },
      ("Deprecated: use " + new_name).c_str());
}

}  // namespace plumekit::python
