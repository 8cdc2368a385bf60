"""The server's edge (installed by serve.py): what every request and websocket meets first."""


def base_path() -> str:
    """The app's path prefix on its server ("/dynamics-lab", or "" at the root): Streamlit's
    ``server.baseUrlPath``, however many slashes it was given with."""
    from streamlit import config

    base = "/".join(p for p in (config.get_option("server.baseUrlPath") or "").split("/") if p)
    return f"/{base}" if base else ""
