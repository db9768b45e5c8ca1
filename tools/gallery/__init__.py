"""The main job's building blocks: the lessons' runs, their outputs' manifests, the texts' figures, the decks,
the rendered texts and out/index.html (tools/main_job.py, tools/figures.py, tests/checks/check_outputs.py)."""


class JobError(Exception):
    """A step of the main job failed; the message says why (tools/main_job.py prints it and exits 1)."""
