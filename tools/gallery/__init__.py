"""The main job's building blocks: discovery, output checks, decks and out/index.html.

Used by tools/main_job.py and tools/check_outputs.py; unit-tested by
tests/tools/test_gallery.py. Standard library only.
"""
