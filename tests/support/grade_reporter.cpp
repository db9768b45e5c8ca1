// Placeholder: the grading reporter is registered here.
