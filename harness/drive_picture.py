"""Picture of a drive at its assembled initial pose (PNG).

    python -m harness.drive_picture [--drive FILE] [--out docs/default_drive.png]
"""
import argparse

from . import paths, plots


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--drive", help="drive description (default: the embedded default drive)")
    ap.add_argument("--out", default=str(paths.ROOT / "docs" / "default_drive.png"))
    args = ap.parse_args(argv)
    plots.drive_picture(args.out, args.drive)
    print(f"written: {args.out}")


if __name__ == "__main__":
    main()
