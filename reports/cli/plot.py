"""``bouncer plot RUN_DIR``: the survival curves (the portrait, <v_n>) of a run, as PNG."""

from reports.stats.plot import FIT_CHOICES, plot_run


def _plot(args):
    for line in plot_run(args.run_dir, out=args.out, fit=args.fit, window=args.window,
                         clock=args.clock, curve=args.curve):
        print(line)
    return 0


def add_parser(subparsers):
    plot = subparsers.add_parser(
        "plot", help="survival curves (the portrait, <v_n>) of a run, as PNG")
    plot.add_argument("run_dir", metavar="RUN_DIR", help="the run directory to draw")
    plot.add_argument("--out", help="image file (default: RUN_DIR/survival.png, portrait.png"
                                    " or velocity.png)")
    plot.add_argument("--fit", choices=list(FIT_CHOICES),
                      help="maximum-likelihood fits as `bouncer fit`: 'regimes' draws its law of"
                      " every regime; a law name fits that law over --window")
    plot.add_argument("--window", type=float, nargs=2, metavar=("LO", "HI"),
                      help="the range of the clock the fit uses")
    plot.add_argument("--clock", choices=["collisions", "time"], default="time",
                      help="the clock of the fitted curves (default time)")
    plot.add_argument("--curve", help="fit only this curve")
    plot.set_defaults(func=_plot)
