"""Benchmarks of the BVH and of the edit-test loop, and their tables."""
