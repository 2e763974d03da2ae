"""Mission-independent software-in-the-loop machinery: campaign runner, failure criteria, reports."""
