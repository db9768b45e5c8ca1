"""The main job's building blocks: the lessons' runs, their outputs' manifests, the texts' figures, the decks,
the rendered texts and out/index.html (tools/main_job.py, tools/figures.py, tests/checks/check_outputs.py)."""
