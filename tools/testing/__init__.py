"""Running the tests: GoogleTest binaries and the tools' own Python tests,
side by side on every core."""
