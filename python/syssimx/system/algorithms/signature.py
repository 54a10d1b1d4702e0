"""Constructor signatures that show the engine's defaults.

An option whose default the engine defines is a dataclass field with a `default_factory`, so
`help()` and the API reference would show it as `<factory>`. `EngineDefaults` is the class's
`__signature__`: the constructor's, with each factory's value in its place. It is computed when
asked for (reading the defaults loads the engine), never at import."""

from __future__ import annotations

import dataclasses
import inspect
from typing import Any


class EngineDefaults:
    """A class attribute `__signature__ = EngineDefaults()` of a dataclass."""

    def __get__(self, instance: object, owner: type) -> inspect.Signature:
        # an instance is not callable; while @dataclass builds the class it has no fields yet
        if instance is not None or not dataclasses.is_dataclass(owner):
            raise AttributeError("__signature__")
        constructor = inspect.signature(owner.__init__)
        factories = {field.name: field.default_factory for field in dataclasses.fields(owner)
                     if field.default_factory is not dataclasses.MISSING}
        parameters: list[inspect.Parameter] = []
        for parameter in list(constructor.parameters.values())[1:]:  # without self
            factory: Any = factories.get(parameter.name)
            parameters.append(parameter if factory is None
                              else parameter.replace(default=factory()))
        return constructor.replace(parameters=parameters,
                                   return_annotation=inspect.Signature.empty)
