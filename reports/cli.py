"""The ``bouncer`` command. Exit status: 0 ok, 1 failure, 2 bad input (one-line message)."""

import argparse
import sys


def _demo(args):
    from reports.demo import run_demo

    run_demo(eps=args.eps, collisions=args.collisions, sample=args.sample, seed=args.seed)
    return 0


def build_parser():
    parser = argparse.ArgumentParser(
        prog="bouncer", description="Validated numerics for the bouncer model.")
    sub = parser.add_subparsers(dest="command", required=True)
    demo = sub.add_parser("demo", help="an orbit with fastpath, a sample of it checked by verify")
    demo.add_argument("--eps", type=float, default=0.6)
    demo.add_argument("--collisions", type=int, default=100_000)
    demo.add_argument("--sample", type=int, default=200)
    demo.add_argument("--seed", type=int, default=0)
    demo.set_defaults(func=_demo)
    return parser


def main(argv=None):
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return args.func(args)
    except ValueError as err:
        print(f"bouncer: error: {err}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
