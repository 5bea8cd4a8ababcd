"""Batch work over an executor (local processes or Ray): `h3ds batch generate`, `h3ds data build`,
`h3ds bench placement`. See app.batch.executors and app.batch.scenes."""
