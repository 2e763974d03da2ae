"""Typed kernel configurations that cannot drift from the C structs.

A `KernelConfig` subclass names only its C struct and its ``ogk_<law>_config_default``; the fields,
their types and their defaults come from the kernel itself:

    cfg = CpdConfig(k_px=..., pointing=Pointing.BODY)    # ogk_cpd_config_default, then each field by name
    cfg.k_px, cfg.as_dict(), cfg.replace(phi_c=0.1), cfg.to_c()

* every name is checked against ``ffi.typeof(struct).fields`` (unknown name: TypeError), so a field
  added to the C struct is settable at once and none is silently zeroed by ``ffi.new``;
* fields not given keep the C default (the defaults live in C only);
* array fields take any sequence no longer than the C array (the rest keeps its default);
  ``_array_lengths`` may say how many entries of an array are meaningful (what the getter returns);
* instances are immutable (``replace`` makes a new one) and compare by field values;
* a pointer field (a table the kernel reads in place, ogk_nog_config_t.table) keeps the object it
  points to alive as long as the configuration: the kernel does not copy it, and cffi frees an
  owning cdata that nothing references. ``to_c()`` copies the pointer only, so keep the
  configuration while the copy is in use.
"""
from __future__ import annotations

from typing import Any, ClassVar

import numpy as np

from ogk_bindings._ffi import ffi, lib
from ogk_bindings.kernel import _check

__all__ = ["KernelConfig", "field_names"]


def field_names(ctype: str) -> tuple[str, ...]:
    """Field names of a C struct typedef, in declaration order (from the compiled bindings)."""
    return tuple(name for name, _ in ffi.typeof(ctype).fields)


def _is_pointer(ftype: Any) -> bool:
    return ftype.kind == "pointer"


#: the C names of a floating field: the kernel's ogk_real_t is double, or float in a single-precision
#: process (ogk_bindings._ffi.PRECISION); a Python float either way
_REAL_CNAMES = ("double", "float")


def _set_field(owner: str, c: Any, name: str, ftype: Any, value: Any) -> None:
    """c.name = value, by the field's C type; a nested struct takes a mapping of its fields."""
    if _is_pointer(ftype):
        setattr(c, name, ffi.NULL if value is None else value)
    elif ftype.kind == "struct":
        sub = getattr(c, name)
        fields = dict(ftype.fields)
        for key, v in dict(value).items():
            if key not in fields:
                raise TypeError(f"{owner}.{name} has no field {key!r}; fields: {', '.join(fields)}")
            _set_field(f"{owner}.{name}", sub, key, fields[key].type, v)
    elif ftype.kind == "array":
        v = np.asarray(value, dtype=np.float64 if ftype.item.cname in _REAL_CNAMES else np.int64)
        v = v.reshape(-1)
        if v.size > ftype.length:
            raise ValueError(f"{owner}.{name}: {v.size} values, the C array holds {ftype.length}")
        arr = getattr(c, name)
        for i, x in enumerate(v):
            arr[i] = float(x) if ftype.item.cname in _REAL_CNAMES else int(x)
    elif ftype.kind == "enum" or (ftype.kind == "primitive" and ftype.cname not in _REAL_CNAMES):
        setattr(c, name, int(value))
    else:
        setattr(c, name, float(value))


def _get_field(value: Any, ftype: Any) -> Any:
    """A nested struct's fields as a dict (arrays as numpy arrays)."""
    if ftype.kind == "struct":
        return {k: _get_field(getattr(value, k), f.type) for k, f in ftype.fields}
    if ftype.kind == "array":
        return np.array([value[i] for i in range(ftype.length)])
    if ftype.kind == "primitive" and ftype.cname in _REAL_CNAMES:
        return float(value)
    return int(value)


class KernelConfig:
    """Base of the typed configurations: subclasses set ``_ctype`` and ``_default_fn``."""

    _ctype: ClassVar[str]
    _default_fn: ClassVar[str]

    def __init__(self, **fields: Any) -> None:
        c = ffi.new(f"{self._ctype} *")
        _check(getattr(lib, self._default_fn)(c), self._default_fn)
        object.__setattr__(self, "_c", c)
        object.__setattr__(self, "_targets", {})
        for name, value in fields.items():
            self._set(name, value)
        self._validate()

    # ----------------------------------------------------------------- fields
    @classmethod
    def fields(cls) -> tuple[str, ...]:
        return field_names(cls._ctype)

    @classmethod
    def _ftype(cls, name: str) -> Any:
        for fname, f in ffi.typeof(cls._ctype).fields:
            if fname == name:
                return f.type
        raise TypeError(f"{cls._ctype} has no field {name!r}; fields: {', '.join(cls.fields())}")

    def _set(self, name: str, value: Any) -> None:
        ftype = self._ftype(name)
        _set_field(self._ctype, self._c, name, ftype, value)
        if _is_pointer(ftype):      # what the pointer points to lives as long as this config
            self._targets[name] = value

    def _validate(self) -> None:
        """Hook for checks the C init cannot word as well (subclasses)."""

    _enums: ClassVar[dict[str, Any]] = {}  #: field -> Python enum its value is returned as

    def _array_lengths(self) -> dict[str, int]:
        """Meaningful entries of array fields (default: the whole C array)."""
        return {}

    def __getattr__(self, name: str) -> Any:
        if name.startswith("_"):
            raise AttributeError(name)
        ftype = self._ftype(name)
        value = getattr(self._c, name)
        if ftype.kind == "array":
            n = self._array_lengths().get(name, ftype.length)
            return np.array([value[i] for i in range(n)])
        if _is_pointer(ftype):
            return value
        if ftype.kind == "struct":
            return _get_field(value, ftype)
        if ftype.kind == "primitive" and ftype.cname in _REAL_CNAMES:
            return float(value)
        if name in self._enums:
            return self._enums[name](int(value))
        return int(value)

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError(f"{type(self).__name__} is immutable: use .replace({name}=...)")

    # ----------------------------------------------------------------- whole struct
    def as_dict(self) -> dict[str, Any]:
        return {name: getattr(self, name) for name in self.fields()}

    def replace(self, **changes: Any) -> "KernelConfig":
        new = type(self).__new__(type(self))
        c = ffi.new(f"{self._ctype} *")
        ffi.memmove(c, self._c, ffi.sizeof(self._ctype))
        object.__setattr__(new, "_c", c)
        object.__setattr__(new, "_targets", dict(self._targets))
        for name, value in changes.items():
            new._set(name, value)
        new._validate()
        return new

    def to_c(self) -> Any:
        """A fresh ``<struct> *`` holding this configuration (caller-owned copy)."""
        c = ffi.new(f"{self._ctype} *")
        ffi.memmove(c, self._c, ffi.sizeof(self._ctype))
        return c

    def __eq__(self, other: object) -> bool:
        if type(other) is not type(self):
            return NotImplemented
        return bytes(ffi.buffer(self._c)) == bytes(ffi.buffer(other._c))  # type: ignore[attr-defined]

    def __hash__(self) -> int:
        return hash(bytes(ffi.buffer(self._c)))

    def __repr__(self) -> str:
        parts = []
        for name, value in self.as_dict().items():
            text = np.array2string(value, threshold=6) if isinstance(value, np.ndarray) else repr(value)
            parts.append(f"{name}={text}")
        return f"{type(self).__name__}({', '.join(parts)})"
