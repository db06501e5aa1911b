"""`python -m gearcli` entry point."""

from gearcli.cli import main

if __name__ == "__main__":
    main()
