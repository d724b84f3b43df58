#pragma once
// Binding an options field: its name, its library default (the struct's own), and its help.
#include <pybind11/pybind11.h>

// c.def_readwrite("name", &Type::name, doc)
#define PK_FIELD(cls, Type, name, doc) (cls).def_readwrite(#name, &Type::name, doc)
