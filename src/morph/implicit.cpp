// Placeholder: implemented in the issue-14 branch for this file.
