#!/usr/bin/env python3
"""Write compile_commands.json for the readable tangle, so clangd and IDEs
index tangled/ and tests/ with the flags the build uses."""
import argparse
import glob
import json
import os

parser = argparse.ArgumentParser()
parser.add_argument('--src', required=True)
args = parser.parse_args()
root = os.getcwd()
files = sorted(glob.glob(os.path.join(args.src, '**', '*.cpp'), recursive=True) +
               glob.glob('tests/**/*.cpp', recursive=True))
print(json.dumps([{
    'directory': root,
    'file': f,
    'arguments': ['g++', '-std=c++17', '-Wall', '-Wextra', '-I' + args.src, '-c', f],
} for f in files], indent=1))
