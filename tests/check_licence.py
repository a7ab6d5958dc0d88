#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""Every source file git tracks names the project's licence in its first three lines (an SPDX identifier),
and LICENSE holds the licence's text: a packager can tell what each file is under. Usage:
  python3 tests/check_licence.py SOURCE_ROOT"""
import subprocess
import sys
from pathlib import Path

TAG = 'SPDX-License-Identifier: LGPL-2.1-or-later'
SUFFIXES = ('.cpp', '.hpp', '.h', '.c', '.cjs', '.py', '.sh', '.service')
NAMES = ('meson.build', 'meson_options.txt', '.clang-format')


def needs_tag(path):
    return path.endswith(SUFFIXES) or path.rsplit('/', 1)[-1] in NAMES


def main(root):
    root = Path(root)
    try:
        listed = subprocess.run(['git', '-C', str(root), 'ls-files'], capture_output=True, text=True, check=True)
    except (OSError, subprocess.CalledProcessError) as error:
        print(f'SKIPPED: {root} is not a git work tree with git installed ({error})')
        return 77
    missing = []
    for path in filter(needs_tag, listed.stdout.split()):
        with open(root / path, encoding='utf-8', errors='replace') as f:
            head = [f.readline() for _ in range(3)]
        if not any(TAG in line for line in head):
            missing.append(path)
    for path in missing:
        print(f'FAIL: {path}: no "{TAG}" in its first three lines')
    licence = root / 'LICENSE'
    text_found = licence.is_file() and 'GNU LESSER GENERAL PUBLIC LICENSE' in licence.read_text()[:200]
    if not text_found:
        print('FAIL: LICENSE does not hold the LGPL-2.1 text')
    print(f'{len(missing)} file(s) without the licence identifier')
    return 1 if missing or not text_found else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else '.'))
