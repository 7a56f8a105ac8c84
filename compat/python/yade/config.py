"""`yade.config`: build information, as YADE's (the version ryade reproduces)."""
version = '2023.02a'
revision = 'ryade'
prefix = '/usr'
suffix = ''
features = ['ryade']
