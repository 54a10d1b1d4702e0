"""The bridge between the API classes and the engine: a System compiled into an engine system
(plan), the Python side of the engine's callbacks, engine failures as exceptions, and the
recorded history as arrays. components/ and system/ build on it; it imports neither."""
