"""What the grading, gallery and check tools share: Markdown, C++ source text, PNG, atomic files."""
