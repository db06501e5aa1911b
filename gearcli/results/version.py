"""The version of gearcli's JSON result documents."""

#: Version of gearcli's JSON result documents (summary.json, analysis.json, stress.json and the
#: JSON of modal and mesh): every document carries it as "schema_version"; raised when a key
#: is renamed or removed (added keys keep it).
RESULTS_SCHEMA_VERSION = 1
